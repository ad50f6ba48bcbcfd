// energy_test.cpp: placeholder
