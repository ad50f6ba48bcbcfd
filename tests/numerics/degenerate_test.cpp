// degenerate_test.cpp: placeholder
