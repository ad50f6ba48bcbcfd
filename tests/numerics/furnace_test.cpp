// furnace_test.cpp: placeholder
