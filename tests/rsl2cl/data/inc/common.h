/* common.h: included by preprocessor tests. */
#define SCALE 2
#define TWICE(x) ((x) * SCALE)
float helper() { return undefined_here; }
