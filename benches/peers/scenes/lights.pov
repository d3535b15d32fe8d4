#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 3 ambient_light 0 }
background { rgb <0.05, 0.05, 0.06> }
camera { perspective location <0, 5, 7> look_at <0, 0, 0> sky y right x up y angle 45 }
light_source { <5, 3, 0> color rgb 0.06 }
light_source { <4.82963, 4, 1.2941> color rgb 0.06 }
light_source { <4.33013, 5, 2.5> color rgb 0.06 }
light_source { <3.53553, 3, 3.53553> color rgb 0.06 }
light_source { <2.5, 4, 4.33013> color rgb 0.06 }
light_source { <1.2941, 5, 4.82963> color rgb 0.06 }
light_source { <3.06162e-16, 3, 5> color rgb 0.06 }
light_source { <-1.2941, 4, 4.82963> color rgb 0.06 }
light_source { <-2.5, 5, 4.33013> color rgb 0.06 }
light_source { <-3.53553, 3, 3.53553> color rgb 0.06 }
light_source { <-4.33013, 4, 2.5> color rgb 0.06 }
light_source { <-4.82963, 5, 1.2941> color rgb 0.06 }
light_source { <-5, 3, 6.12323e-16> color rgb 0.06 }
light_source { <-4.82963, 4, -1.2941> color rgb 0.06 }
light_source { <-4.33013, 5, -2.5> color rgb 0.06 }
light_source { <-3.53553, 3, -3.53553> color rgb 0.06 }
light_source { <-2.5, 4, -4.33013> color rgb 0.06 }
light_source { <-1.2941, 5, -4.82963> color rgb 0.06 }
light_source { <-9.18485e-16, 3, -5> color rgb 0.06 }
light_source { <1.2941, 4, -4.82963> color rgb 0.06 }
light_source { <2.5, 5, -4.33013> color rgb 0.06 }
light_source { <3.53553, 3, -3.53553> color rgb 0.06 }
light_source { <4.33013, 4, -2.5> color rgb 0.06 }
light_source { <4.82963, 5, -1.2941> color rgb 0.06 }
light_source { <-2, 4.5, -2> color rgb 0.12 area_light <0.4, 0, 0>, <0, 0, 0.4>, 2, 2 jitter }
light_source { <-2, 4.5, 2> color rgb 0.12 area_light <0.4, 0, 0>, <0, 0, 0.4>, 2, 2 jitter }
light_source { <2, 4.5, -2> color rgb 0.12 area_light <0.4, 0, 0>, <0, 0, 0.4>, 2, 2 jitter }
light_source { <2, 4.5, 2> color rgb 0.12 area_light <0.4, 0, 0>, <0, 0, 0.4>, 2, 2 jitter }
mesh2 { vertex_vectors { 4, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { uv_mapping image_map { png "checker.png" interpolate 2 } } finish { ambient 0 diffuse 0.8 specular 0.1 roughness 0.1 } } }
sphere { <-2.4, 0.4, -2.4>, 0.4 texture { pigment { rgb <0.85, 0.4, 0.4> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.4, 0.4, -1.2>, 0.4 texture { pigment { rgb <0.328784, 0.836101, 0.485115> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.4, 0.4, 0>, 0.4 texture { pigment { rgb <0.576243, 0.278067, 0.79569> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.4, 0.4, 1.2>, 0.4 texture { pigment { rgb <0.732514, 0.664939, 0.252548> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.4, 0.4, 2.4>, 0.4 texture { pigment { rgb <0.254591, 0.652425, 0.742984> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.2, 0.4, -2.4>, 0.4 texture { pigment { rgb <0.803147, 0.284008, 0.562845> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.2, 0.4, -1.2>, 0.4 texture { pigment { rgb <0.472075, 0.839852, 0.338072> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.2, 0.4, 0>, 0.4 texture { pigment { rgb <0.411775, 0.388526, 0.8497> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.2, 0.4, 1.2>, 0.4 texture { pigment { rgb <0.831776, 0.498285, 0.319939> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.2, 0.4, 2.4>, 0.4 texture { pigment { rgb <0.272671, 0.787742, 0.589588> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0, 0.4, -2.4>, 0.4 texture { pigment { rgb <0.677222, 0.2511, 0.721678> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0, 0.4, -1.2>, 0.4 texture { pigment { rgb <0.639706, 0.753067, 0.257226> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0, 0.4, 0>, 0.4 texture { pigment { rgb <0.290482, 0.549422, 0.810096> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0, 0.4, 1.2>, 0.4 texture { pigment { rgb <0.843024, 0.347785, 0.459191> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0, 0.4, 2.4>, 0.4 texture { pigment { rgb <0.377375, 0.848799, 0.423826> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.2, 0.4, -2.4>, 0.4 texture { pigment { rgb <0.511559, 0.311555, 0.826887> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.2, 0.4, -1.2>, 0.4 texture { pigment { rgb <0.779317, 0.602853, 0.26783> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.2, 0.4, 0>, 0.4 texture { pigment { rgb <0.250251, 0.710499, 0.68925> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.2, 0.4, 1.2>, 0.4 texture { pigment { rgb <0.762744, 0.260448, 0.626808> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.2, 0.4, 2.4>, 0.4 texture { pigment { rgb <0.536, 0.816525, 0.297476> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.4, 0.4, -2.4>, 0.4 texture { pigment { rgb <0.357903, 0.446489, 0.845608> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.4, 0.4, -1.2>, 0.4 texture { pigment { rgb <0.8473, 0.43613, 0.36657> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.4, 0.4, 0>, 0.4 texture { pigment { rgb <0.303648, 0.821443, 0.524909> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.4, 0.4, 1.2>, 0.4 texture { pigment { rgb <0.616013, 0.263554, 0.770433> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.4, 0.4, 2.4>, 0.4 texture { pigment { rgb <0.698998, 0.701, 0.250002> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
