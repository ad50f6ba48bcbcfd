/* all_types.h: every shared struct, for code that needs them all (the layout probe). */
#ifndef RT_ALL_TYPES_H
#define RT_ALL_TYPES_H
#include "bvh.h"
#include "film.h"
#include "quadric.h"
#include "ray.h"
#include "scene_types.h"
#include "texture.h"
#include "treelet.h"
#endif
