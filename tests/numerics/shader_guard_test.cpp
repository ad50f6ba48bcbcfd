// shader_guard_test.cpp: placeholder
