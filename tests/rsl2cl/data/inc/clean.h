/* clean.h: an include with only macros. */
#ifndef CLEAN_H
#define CLEAN_H
#define KD_DEFAULT 0.75
#endif
