#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 9 ambient_light 0 }
background { rgb <0.3, 0.35, 0.45> }
camera { perspective location <0, 3, 7.5> look_at <0, 0.6, 0> sky y right x up y angle 45 }
light_source { <-3, 6, 5> color rgb 0.9 }
mesh2 { vertex_vectors { 4, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { uv_mapping image_map { png "checker.png" interpolate 2 } } finish { ambient 0 diffuse 0.8 specular 0.1 roughness 0.1 } } }
mesh2 { vertex_vectors { 4, <-6, 0, -3>, <6, 0, -3>, <6, 5, -3>, <-6, 5, -3> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-2.2, 0.8, -1.8>, 0.8 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-2.2, 0.8, 0>, 0.8 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-2.2, 0.8, 1.8>, 0.8 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <0, 0.8, -1.8>, 0.8 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <0, 0.8, 0>, 0.8 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <0, 0.8, 1.8>, 0.8 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.2, 0.8, -1.8>, 0.8 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <2.2, 0.8, 0>, 0.8 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.2, 0.8, 1.8>, 0.8 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
