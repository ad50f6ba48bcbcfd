// transform_test.cpp: placeholder
