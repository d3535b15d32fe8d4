#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 13 ambient_light 0 }
background { rgb <0.3, 0.35, 0.45> }
camera { perspective location <1.6, 1.5, 3.5> look_at <-2.2, 1, 0.5> sky y right x up y angle 55 }
light_source { <0, 3.6, 2.5> color rgb 0.9 }
mesh2 { vertex_vectors { 4, <-5, 0, 5>, <5, 0, 5>, <5, 0, -5>, <-5, 0, -5> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { uv_mapping image_map { png "checker.png" interpolate 2 } } finish { ambient 0 diffuse 0.8 specular 0.1 roughness 0.1 } } }
mesh2 { vertex_vectors { 4, <-2.2, 0, 6>, <-2.2, 0, -6>, <-2.2, 6, -6>, <-2.2, 6, 6> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
mesh2 { vertex_vectors { 4, <2.2, 0, 6>, <2.2, 0, -6>, <2.2, 6, -6>, <2.2, 6, 6> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-0.6, 0.8, -0.5>, 0.8 texture { pigment { rgb <0.9, 0.2, 0.15> } finish { ambient 0 diffuse 0.8 specular 0.4 roughness 0.0333333 } } }
sphere { <1, 0.5, 1.2>, 0.5 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
