#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 3 ambient_light 0 }
background { rgb <0.05, 0.05, 0.06> }
camera { perspective location <0, 3, 7> look_at <0, 0.5, 0> sky y right x up y angle 40 }
light_source { <0, 4, 0.5> color rgb 1 area_light <4, 0, 0>, <0, 0, 4>, 16, 16 jitter }
mesh2 { vertex_vectors { 4, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { uv_mapping image_map { png "checker.png" interpolate 2 } } finish { ambient 0 diffuse 0.8 specular 0.1 roughness 0.1 } } }
sphere { <-2.4, 0.7, -0>, 0.7 texture { pigment { rgb <0.85, 0.4, 0.4> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.8, 0.7, -0.3>, 0.7 texture { pigment { rgb <0.576243, 0.278067, 0.79569> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.8, 0.7, -0.6>, 0.7 texture { pigment { rgb <0.254591, 0.652425, 0.742984> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.4, 0.7, -0.9>, 0.7 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
