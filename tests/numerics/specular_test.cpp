// specular_test.cpp: placeholder
