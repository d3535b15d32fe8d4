#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 9 ambient_light 0 }
background { rgb <0.1, 0.12, 0.16> }
camera { perspective location <0, 5, 8> look_at <0, 0, -0.5> sky y right x up y angle 45 }
light_source { <-4, 7, 5> color rgb 0.6 }
light_source { <3, 6, 2> color rgb 0.5 area_light <1, 0, 0>, <0, 0, 1>, 4, 4 jitter }
mesh2 { vertex_vectors { 4, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6> } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { pigment { uv_mapping image_map { png "checker.png" interpolate 2 } } finish { ambient 0 diffuse 0.8 specular 0.1 roughness 0.1 } } }
sphere { <-4.5, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.85, 0.4, 0.4> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, -3.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-4.5, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.576243, 0.278067, 0.79569> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, -2.7>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-4.5, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.254591, 0.652425, 0.742984> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.803147, 0.284008, 0.562845> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, -0.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-4.5, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.411775, 0.388526, 0.8497> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.831776, 0.498285, 0.319939> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.272671, 0.787742, 0.589588> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, 1.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-4.5, 0.25, 2.1>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-4.5, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.290482, 0.549422, 0.810096> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.843024, 0.347785, 0.459191> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.377375, 0.848799, 0.423826> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-4.5, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.511559, 0.311555, 0.826887> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, -4.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-3.9, 0.25, -3.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-3.9, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.762744, 0.260448, 0.626808> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.536, 0.816525, 0.297476> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.357903, 0.446489, 0.845608> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, -1.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-3.9, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.303648, 0.821443, 0.524909> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.616013, 0.263554, 0.770433> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, 0.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-3.9, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.264249, 0.613756, 0.771995> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, 1.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-3.9, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.433994, 0.8476, 0.368405> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.448662, 0.356132, 0.845205> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.815455, 0.53831, 0.296235> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.259852, 0.761108, 0.629041> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.9, 0.25, 4.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-3.3, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.600576, 0.780801, 0.268623> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.312965, 0.509267, 0.827768> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.848997, 0.379271, 0.421732> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.346083, 0.842519, 0.461398> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, -2.1>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-3.3, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.751359, 0.64191, 0.256731> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, -0.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-3.3, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.789145, 0.273561, 0.587295> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.496009, 0.832561, 0.32143> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, 0.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-3.3, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.839248, 0.47431, 0.336442> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.282947, 0.801898, 0.565155> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.654595, 0.254197, 0.741208> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-3.3, 0.25, 3.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-3.3, 0.25, 3.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-3.3, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.836788, 0.330353, 0.48286> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.398002, 0.849991, 0.402007> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.487375, 0.327229, 0.835396> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.794356, 0.578545, 0.277099> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, -2.7>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-2.7, 0.25, -2.1>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-2.7, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.560535, 0.80438, 0.285085> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.339715, 0.469845, 0.84044> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.849587, 0.413831, 0.386582> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, 0.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-2.7, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.591878, 0.271797, 0.786325> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.719777, 0.679312, 0.250911> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, 2.1>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-2.7, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.811241, 0.29165, 0.54711> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, 3.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-2.7, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.425928, 0.375489, 0.848583> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.7, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.825988, 0.513853, 0.310159> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.267053, 0.77782, 0.605128> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.691294, 0.250165, 0.70854> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, -3.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-2.1, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.298731, 0.533691, 0.817578> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.845994, 0.359684, 0.444322> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.364746, 0.846981, 0.438273> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.527214, 0.302336, 0.82045> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, -0.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-2.1, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.25002, 0.696986, 0.702994> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, 0.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-2.1, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.520304, 0.82338, 0.306316> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.370251, 0.431866, 0.847883> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, 2.7>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-2.1, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.295009, 0.81437, 0.540621> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.631269, 0.259273, 0.759459> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-2.1, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.685138, 0.714386, 0.250476> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, -4.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-1.5, 0.25, -3.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-1.5, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.419646, 0.849177, 0.381178> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.463609, 0.344393, 0.841997> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.807761, 0.554046, 0.288193> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.256252, 0.749639, 0.644108> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, -0.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-1.5, 0.25, -0.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-1.5, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.322934, 0.493736, 0.833329> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.849871, 0.392442, 0.407687> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.334825, 0.838625, 0.47655> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, 2.1>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-1.5, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.73942, 0.656759, 0.25382> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.253184, 0.660653, 0.736162> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-1.5, 0.25, 3.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-1.5, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.480608, 0.837458, 0.331934> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, -4.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-0.9, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.834675, 0.489638, 0.325687> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.276146, 0.793008, 0.580846> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.669196, 0.251982, 0.728822> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.648066, 0.746501, 0.255432> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, -1.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-0.9, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.841011, 0.341371, 0.467619> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.384648, 0.849457, 0.415895> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.502846, 0.316999, 0.830155> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.784893, 0.594167, 0.27094> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, 1.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-0.9, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.756447, 0.25827, 0.635283> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, 2.7>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-0.9, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.351225, 0.454795, 0.84398> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.84835, 0.428036, 0.373614> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.9, 0.25, 4.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-0.3, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.607399, 0.266293, 0.776308> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.706573, 0.69333, 0.250097> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.261692, 0.622329, 0.765979> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, -2.7>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-0.3, 0.25, -2.1>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-0.3, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.440422, 0.362933, 0.846645> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.819441, 0.52952, 0.301038> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.262213, 0.76727, 0.620516> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.704978, 0.250056, 0.694966> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, 0.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-0.3, 0.25, 1.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <-0.3, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.848149, 0.372108, 0.429744> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.352626, 0.844347, 0.453027> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.542932, 0.293798, 0.813269> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <-0.3, 0.25, 3.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <-0.3, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.250615, 0.68307, 0.716316> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.783728, 0.27026, 0.596012> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, -3.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <0.3, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.383094, 0.417567, 0.849339> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, -2.7>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <0.3, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.287072, 0.80657, 0.556358> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.646301, 0.255791, 0.747908> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.670906, 0.72732, 0.251773> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.27539, 0.582702, 0.791909> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, 0.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <0.3, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.405656, 0.84993, 0.394415> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.478794, 0.33322, 0.837986> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.799357, 0.569771, 0.280872> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.253461, 0.737622, 0.658917> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, 3.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <0.3, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.569326, 0.799605, 0.281069> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.3, 0.25, 4.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <0.9, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.84992, 0.406047, 0.394033> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.324158, 0.833937, 0.491904> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, -3.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <0.9, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.72696, 0.671315, 0.251725> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.255879, 0.645878, 0.748243> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.806801, 0.287287, 0.555912> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, -0.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <0.9, 0.25, -0.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <0.9, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.82932, 0.505131, 0.315549> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.2701, 0.783448, 0.596452> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.683469, 0.250586, 0.715944> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.633064, 0.758119, 0.258818> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, 2.7>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <0.9, 0.25, 3.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <0.9, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.371749, 0.848099, 0.430153> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <0.9, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.518448, 0.307409, 0.824143> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.774784, 0.609667, 0.265549> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, -3.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <1.5, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.767578, 0.26234, 0.620082> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.529075, 0.819637, 0.301288> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, -2.1>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <1.5, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.846292, 0.442578, 0.361131> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, -0.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <1.5, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.622761, 0.261569, 0.76567> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.692938, 0.706953, 0.250109> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.266438, 0.606961, 0.776601> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.825251, 0.309042, 0.515706> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, 2.1>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <1.5, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.455218, 0.350891, 0.843891> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.812153, 0.545244, 0.292603> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.258166, 0.756123, 0.635711> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <1.5, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.718235, 0.250772, 0.680993> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, -4.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.1, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.31728, 0.502406, 0.830314> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, -3.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <2.1, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.34105, 0.840902, 0.468048> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.55867, 0.285966, 0.805364> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, -1.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.1, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.252033, 0.668787, 0.72918> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.793269, 0.276329, 0.580402> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.489201, 0.834816, 0.325983> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, 0.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <2.1, 0.25, 1.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.1, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.279858, 0.798064, 0.572078> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.661068, 0.25312, 0.735812> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.656342, 0.739766, 0.253892> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.282102, 0.567018, 0.80088> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.1, 0.25, 4.5>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.7, 0.25, -4.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <2.7, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.494174, 0.322643, 0.833182> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.790267, 0.585442, 0.274291> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.251486, 0.725088, 0.673426> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, -2.1>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.7, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.5536, 0.807989, 0.288411> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.344718, 0.463182, 0.842099> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, -0.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <2.7, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.314113, 0.828468, 0.507419> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, 0.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <2.7, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.714013, 0.685536, 0.250451> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.259383, 0.630839, 0.759778> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.814581, 0.295244, 0.540175> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.450421, 0.844867, 0.354712> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <2.7, 0.25, 3.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <2.7, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.823196, 0.520748, 0.306056> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.264823, 0.773246, 0.611931> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.697375, 0.250015, 0.70261> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.617832, 0.769163, 0.263005> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, -2.7>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <3.3, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.847044, 0.365097, 0.437859> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, -1.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <3.3, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.534136, 0.298488, 0.817376> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.764056, 0.625002, 0.260942> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, 0.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <3.3, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.77811, 0.267201, 0.604689> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.51341, 0.826163, 0.310427> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.375852, 0.425522, 0.848626> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, 2.7>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <3.3, 0.25, 3.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <3.3, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.637924, 0.257639, 0.754437> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.3, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.678909, 0.720144, 0.250946> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.271964, 0.591437, 0.786599> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, -3.9>, 0.25 texture { pigment { rgb <0.83113, 0.318746, 0.500124> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, -3.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <3.9, 0.25, -2.7>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <3.9, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.804143, 0.560981, 0.284876> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.254922, 0.744409, 0.650669> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, -0.9>, 0.25 texture { pigment { rgb <0.731029, 0.252311, 0.66666> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, -0.3>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <3.9, 0.25, 0.3>, 0.25 texture { pigment { rgb <0.327528, 0.486938, 0.835534> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.849994, 0.398387, 0.401619> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, 1.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <3.9, 0.25, 2.1>, 0.25 texture { pigment { rgb <0.574383, 0.27886, 0.796756> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, 2.7>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <3.9, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.254272, 0.654177, 0.741551> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.80214, 0.28315, 0.564709> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <3.9, 0.25, 4.5>, 0.25 texture { pigment { rgb <0.473879, 0.839366, 0.336756> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, -4.5>, 0.25 texture { pigment { rgb <0.410121, 0.390102, 0.849777> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, -3.9>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <4.5, 0.25, -3.3>, 0.25 texture { pigment { rgb <0.273388, 0.788875, 0.587737> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, -2.7>, 0.25 texture { pigment { rgb <0.675529, 0.251265, 0.723205> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, -2.1>, 0.25 texture { pigment { rgb <0.641485, 0.75169, 0.256825> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, -1.5>, 0.25 texture { pigment { rgb <0.289551, 0.551288, 0.809161> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, -0.9>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <4.5, 0.25, -0.3>, 0.25 texture { pigment { rgb <0.378905, 0.84896, 0.422135> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, 0.3>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
sphere { <4.5, 0.25, 0.9>, 0.25 texture { pigment { rgb <0.780516, 0.601015, 0.268469> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, 1.5>, 0.25 texture { pigment { rgb <0.250333, 0.712072, 0.687595> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, 2.1>, 0.25 texture { pigment { rgb <1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection 1 } } }
sphere { <4.5, 0.25, 2.7>, 0.25 texture { pigment { rgb <0.537864, 0.815663, 0.296473> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, 3.3>, 0.25 texture { pigment { rgb <0.356473, 0.448243, 0.845284> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, 3.9>, 0.25 texture { pigment { rgb <0.847544, 0.434406, 0.36805> } finish { ambient 0 diffuse 0.8 specular 0.3 roughness 0.025 } } }
sphere { <4.5, 0.25, 4.5>, 0.25 texture { pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 diffuse 0 specular 0 roughness 0.005 reflection { 0, 1 fresnel on } conserve_energy } } interior { ior 1.5 } }
