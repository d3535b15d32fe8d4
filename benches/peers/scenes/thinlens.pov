#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 9 ambient_light 0 }
background { rgb <0.1, 0.12, 0.16> }
camera { perspective location <0, 2.6, 7.5> look_at <0, 0.9, 0> sky y right x up y angle 40 aperture 0.3 blur_samples 16, 16 confidence 1 variance 0 focal_point <0, 0.774823, -0.55225> }
light_source { <-4, 6, 5> color rgb 0.5 }
light_source { <1.5, 5, 2> color rgb 0.6 area_light <2, 0, 0>, <0, 0, 2>, 2, 2 jitter }
mesh2 { vertex_vectors { 4, <-5, 0, 5>, <5, 0, 5>, <5, 0, -5>, <-5, 0, -5> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { uv_mapping image_map { png "checker.png" interpolate 2 } } finish { ambient 0 diffuse 0.8 specular 0.1 roughness 0.1 } } }
sphere { <-2.2, 1, 0>, 1 texture { pigment { rgb <0.9, 0.2, 0.15> } finish { ambient 0 diffuse 0.8 specular 0.4 roughness 0.0333333 } } }
sphere { <0, 1, -0.6>, 1 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.2, 1, 0.4>, 1 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
