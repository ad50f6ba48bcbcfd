/* ri.h: the RenderMan Interface as C functions (RI 3.2 chapter 4 and appendix C), the
 * library face of RayDrive: a program calls RiBegin, options, RiWorldBegin, attributes
 * and geometry, RiWorldEnd, RiEnd, as it would with PRMan's or Aqsis' libri.
 * RiBegin(RI_NULL) renders each world block on the OpenCL device RAYDRIVE_DEVICE names
 * (else the default one) and writes the image its Display asks for (without one, ri.exr);
 * RiBegin("f.rib") writes the calls to f.rib as RIB instead. Every call goes through the
 * RIB reader's checks (rib/request_feed.h): a bad call is reported through RiErrorHandler
 * as "Ri:N: error: ..." (N: the call's number since RiBegin) and skipped. Strings are
 * const char* here (RtToken, RtString), so C++ string literals need no cast. */
#ifndef RAYDRIVE_RI_H
#define RAYDRIVE_RI_H

#ifdef __cplusplus
extern "C" {
#endif

typedef short RtBoolean;
typedef int RtInt;
typedef float RtFloat;
typedef const char* RtToken;
typedef const char* RtString;
typedef RtFloat RtColor[3];
typedef RtFloat RtPoint[3];
typedef RtFloat RtVector[3];
typedef RtFloat RtNormal[3];
typedef RtFloat RtHpoint[4];
typedef RtFloat RtMatrix[4][4];
typedef RtFloat RtBasis[4][4];
typedef RtFloat RtBound[6];
typedef void* RtPointer;
typedef void RtVoid;
typedef RtPointer RtObjectHandle;
typedef RtPointer RtLightHandle;
typedef RtPointer RtContextHandle;
typedef RtFloat (*RtFilterFunc)(RtFloat, RtFloat, RtFloat, RtFloat);
typedef RtVoid (*RtErrorHandler)(RtInt code, RtInt severity, RtString message);
typedef RtVoid (*RtProcSubdivFunc)(RtPointer data, RtFloat detail);
typedef RtVoid (*RtProcFreeFunc)(RtPointer data);
typedef RtVoid (*RtArchiveCallback)(RtToken, char*, ...);

#define RI_FALSE 0
#define RI_TRUE 1
#define RI_INFINITY 1.0e38f
#define RI_EPSILON 1.0e-10f
#define RI_NULL ((RtToken)0)

/* Error codes (RiLastError, the handler's code) and severities. */
#define RIE_NOERROR 0
#define RIE_NOMEM 1
#define RIE_SYSTEM 2
#define RIE_NOFILE 3
#define RIE_BADFILE 4
#define RIE_VERSION 5
#define RIE_INCAPABLE 11
#define RIE_UNIMPLEMENT 12
#define RIE_LIMIT 13
#define RIE_BUG 14
#define RIE_NOTSTARTED 23
#define RIE_NESTING 24
#define RIE_NOTOPTIONS 25
#define RIE_NOTATTRIBS 26
#define RIE_NOTPRIMS 27
#define RIE_ILLSTATE 28
#define RIE_BADMOTION 29
#define RIE_BADSOLID 30
#define RIE_BADTOKEN 41
#define RIE_RANGE 42
#define RIE_CONSISTENCY 43
#define RIE_BADHANDLE 44
#define RIE_NOSHADER 45
#define RIE_MISSINGDATA 46
#define RIE_SYNTAX 47
#define RIE_MATH 61
#define RIE_INFO 0
#define RIE_WARNING 1
#define RIE_ERROR 2
#define RIE_SEVERE 3

/* The code of the last error reported (RIE_NOERROR after RiBegin). */
extern RtInt RiLastError;

/* Standard tokens. */
extern RtToken RI_FRAMEBUFFER, RI_FILE, RI_RGB, RI_RGBA, RI_RGBZ, RI_RGBAZ, RI_A, RI_Z,
    RI_AZ, RI_PERSPECTIVE, RI_ORTHOGRAPHIC, RI_HIDDEN, RI_PAINT, RI_CONSTANT, RI_SMOOTH,
    RI_FLATNESS, RI_FOV, RI_AMBIENTLIGHT, RI_POINTLIGHT, RI_DISTANTLIGHT, RI_SPOTLIGHT,
    RI_INTENSITY, RI_LIGHTCOLOR, RI_FROM, RI_TO, RI_CONEANGLE, RI_CONEDELTAANGLE,
    RI_BEAMDISTRIBUTION, RI_MATTE, RI_METAL, RI_SHINYMETAL, RI_PLASTIC, RI_PAINTEDPLASTIC,
    RI_KA, RI_KD, RI_KS, RI_ROUGHNESS, RI_KR, RI_TEXTURENAME, RI_SPECULARCOLOR,
    RI_DEPTHCUE, RI_FOG, RI_BUMPY, RI_MINDISTANCE, RI_MAXDISTANCE, RI_BACKGROUND,
    RI_DISTANCE, RI_AMPLITUDE, RI_RASTER, RI_SCREEN, RI_CAMERA, RI_WORLD, RI_OBJECT,
    RI_INSIDE, RI_OUTSIDE, RI_LH, RI_RH, RI_P, RI_PZ, RI_PW, RI_N, RI_NP, RI_CS, RI_OS,
    RI_S, RI_T, RI_ST, RI_BILINEAR, RI_BICUBIC, RI_LINEAR, RI_CUBIC, RI_PRIMITIVE,
    RI_INTERSECTION, RI_UNION, RI_DIFFERENCE, RI_PERIODIC, RI_NONPERIODIC, RI_CLAMP,
    RI_BLACK, RI_IGNORE, RI_PRINT, RI_ABORT, RI_HANDLER, RI_WIDTH, RI_CONSTANTWIDTH;

/* Bases for RiBasis (RiBasis writes their names), with their steps. */
extern RtBasis RiBezierBasis, RiBSplineBasis, RiCatmullRomBasis, RiHermiteBasis,
    RiPowerBasis;
#define RI_BEZIERSTEP 3
#define RI_BSPLINESTEP 1
#define RI_CATMULLROMSTEP 1
#define RI_HERMITESTEP 2
#define RI_POWERSTEP 4

/* Pixel filters (RiPixelFilter takes these by name; another function is an error). */
RtFloat RiBoxFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiTriangleFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiCatmullRomFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiGaussianFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiSincFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
/* PRMan's: a separable catmull-rom, Mitchell-Netravali (B = C = 1/3), Blackman-Harris,
 * Lanczos, and the radial disk and bessel (jinc) within the ellipse of the widths */
RtFloat RiSeparableCatmullRomFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiMitchellFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiBlackmanHarrisFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiLanczosFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiDiskFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiBesselFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);

/* Error handlers: print (the default), ignore, or print and exit(1). Any other function
 * is called with each error and warning instead of printing it. */
RtVoid RiErrorIgnore(RtInt code, RtInt severity, RtString message);
RtVoid RiErrorPrint(RtInt code, RtInt severity, RtString message);
RtVoid RiErrorAbort(RtInt code, RtInt severity, RtString message);

/* Procedurals (RiProcedural takes these by name; data is an RtString array). */
RtVoid RiProcDelayedReadArchive(RtPointer data, RtFloat detail);
RtVoid RiProcRunProgram(RtPointer data, RtFloat detail);
RtVoid RiProcDynamicLoad(RtPointer data, RtFloat detail);
/* A free function for RiProcedural: free(data). RiProcedural copies what it needs and
 * calls the free function given at once. */
RtVoid RiProcFree(RtPointer data);

RtToken RiDeclare(RtString name, RtString declaration);

RtVoid RiBegin(RtToken name);
RtVoid RiEnd(void);
/* Several contexts (RI 3.2): RiBegin makes a new one current, RiGetContext returns the
 * current one (RI_NULL: none), RiContext makes one current again; RiEnd ends the current
 * one and leaves none current. */
RtContextHandle RiGetContext(void);
RtVoid RiContext(RtContextHandle handle);
RtVoid RiFrameBegin(RtInt frame);
RtVoid RiFrameEnd(void);
RtVoid RiWorldBegin(void);
RtVoid RiWorldEnd(void);

/* Options */
RtVoid RiFormat(RtInt xresolution, RtInt yresolution, RtFloat pixelaspectratio);
RtVoid RiFrameAspectRatio(RtFloat frameratio);
RtVoid RiScreenWindow(RtFloat left, RtFloat right, RtFloat bottom, RtFloat top);
RtVoid RiCropWindow(RtFloat xmin, RtFloat xmax, RtFloat ymin, RtFloat ymax);
RtVoid RiProjection(RtToken name, ...);
RtVoid RiProjectionV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiClipping(RtFloat hither, RtFloat yon);
RtVoid RiClippingPlane(RtFloat x, RtFloat y, RtFloat z, RtFloat nx, RtFloat ny,
                       RtFloat nz);
RtVoid RiCamera(RtToken name, ...);
RtVoid RiCameraV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiDepthOfField(RtFloat fstop, RtFloat focallength, RtFloat focaldistance);
RtVoid RiShutter(RtFloat opentime, RtFloat closetime);
RtVoid RiPixelVariance(RtFloat variation);
RtVoid RiPixelSamples(RtFloat xsamples, RtFloat ysamples);
RtVoid RiPixelFilter(RtFilterFunc filterfunc, RtFloat xwidth, RtFloat ywidth);
RtVoid RiExposure(RtFloat gain, RtFloat gamma);
RtVoid RiImager(RtToken name, ...);
RtVoid RiImagerV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiQuantize(RtToken type, RtInt one, RtInt min, RtInt max, RtFloat ampl);
RtVoid RiDisplay(RtToken name, RtToken type, RtToken mode, ...);
RtVoid RiDisplayV(RtToken name, RtToken type, RtToken mode, RtInt n, RtToken tokens[],
                  RtPointer values[]);
RtVoid RiDisplayChannel(RtToken channel, ...);
RtVoid RiDisplayChannelV(RtToken channel, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiHider(RtToken type, ...);
RtVoid RiHiderV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiColorSamples(RtInt n, RtFloat nRGB[], RtFloat RGBn[]);
RtVoid RiRelativeDetail(RtFloat relativedetail);
RtVoid RiOption(RtToken name, ...);
RtVoid RiOptionV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);

/* Attributes */
RtVoid RiAttributeBegin(void);
RtVoid RiAttributeEnd(void);
RtVoid RiColor(RtColor color);
RtVoid RiOpacity(RtColor color);
RtVoid RiTextureCoordinates(RtFloat s1, RtFloat t1, RtFloat s2, RtFloat t2, RtFloat s3,
                            RtFloat t3, RtFloat s4, RtFloat t4);
RtLightHandle RiLightSource(RtToken name, ...);
RtLightHandle RiLightSourceV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtLightHandle RiAreaLightSource(RtToken name, ...);
RtLightHandle RiAreaLightSourceV(RtToken name, RtInt n, RtToken tokens[],
                                 RtPointer values[]);
RtVoid RiIlluminate(RtLightHandle light, RtBoolean onoff);
RtVoid RiSurface(RtToken name, ...);
RtVoid RiSurfaceV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiDisplacement(RtToken name, ...);
RtVoid RiDisplacementV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiAtmosphere(RtToken name, ...);
RtVoid RiAtmosphereV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiInterior(RtToken name, ...);
RtVoid RiInteriorV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiExterior(RtToken name, ...);
RtVoid RiExteriorV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiShadingRate(RtFloat size);
RtVoid RiShadingInterpolation(RtToken type);
RtVoid RiGeometricRepresentation(RtToken type);
RtVoid RiMatte(RtBoolean onoff);
RtVoid RiBound(RtBound bound);
RtVoid RiDetail(RtBound bound);
RtVoid RiDetailRange(RtFloat minvisible, RtFloat lowertransition, RtFloat uppertransition,
                     RtFloat maxvisible);
RtVoid RiGeometricApproximation(RtToken type, RtFloat value);
RtVoid RiOrientation(RtToken orientation);
RtVoid RiReverseOrientation(void);
RtVoid RiSides(RtInt sides);
RtVoid RiAttribute(RtToken name, ...);
RtVoid RiAttributeV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);

/* Transformations */
RtVoid RiIdentity(void);
RtVoid RiTransform(RtMatrix transform);
RtVoid RiConcatTransform(RtMatrix transform);
RtVoid RiPerspective(RtFloat fov);
RtVoid RiTranslate(RtFloat dx, RtFloat dy, RtFloat dz);
RtVoid RiRotate(RtFloat angle, RtFloat dx, RtFloat dy, RtFloat dz);
RtVoid RiScale(RtFloat sx, RtFloat sy, RtFloat sz);
RtVoid RiSkew(RtFloat angle, RtFloat dx1, RtFloat dy1, RtFloat dz1, RtFloat dx2,
              RtFloat dy2, RtFloat dz2);
RtVoid RiDeformation(RtToken name, ...);
RtVoid RiDeformationV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiCoordinateSystem(RtToken space);
RtVoid RiScopedCoordinateSystem(RtToken space);
RtVoid RiCoordSysTransform(RtToken space);
RtPoint* RiTransformPoints(RtToken fromspace, RtToken tospace, RtInt npoints,
                           RtPoint* points);
RtVoid RiTransformBegin(void);
RtVoid RiTransformEnd(void);

/* Geometry */
RtVoid RiPolygon(RtInt nvertices, ...);
RtVoid RiPolygonV(RtInt nvertices, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiGeneralPolygon(RtInt nloops, RtInt nverts[], ...);
RtVoid RiGeneralPolygonV(RtInt nloops, RtInt nverts[], RtInt n, RtToken tokens[],
                         RtPointer values[]);
RtVoid RiPointsPolygons(RtInt npolys, RtInt nverts[], RtInt verts[], ...);
RtVoid RiPointsPolygonsV(RtInt npolys, RtInt nverts[], RtInt verts[], RtInt n,
                         RtToken tokens[], RtPointer values[]);
RtVoid RiPointsGeneralPolygons(RtInt npolys, RtInt nloops[], RtInt nverts[],
                               RtInt verts[], ...);
RtVoid RiPointsGeneralPolygonsV(RtInt npolys, RtInt nloops[], RtInt nverts[],
                                RtInt verts[], RtInt n, RtToken tokens[],
                                RtPointer values[]);
RtVoid RiBasis(RtBasis ubasis, RtInt ustep, RtBasis vbasis, RtInt vstep);
RtVoid RiPatch(RtToken type, ...);
RtVoid RiPatchV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiPatchMesh(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, ...);
RtVoid RiPatchMeshV(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap,
                    RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiNuPatch(RtInt nu, RtInt uorder, RtFloat uknot[], RtFloat umin, RtFloat umax,
                 RtInt nv, RtInt vorder, RtFloat vknot[], RtFloat vmin, RtFloat vmax,
                 ...);
RtVoid RiNuPatchV(RtInt nu, RtInt uorder, RtFloat uknot[], RtFloat umin, RtFloat umax,
                  RtInt nv, RtInt vorder, RtFloat vknot[], RtFloat vmin, RtFloat vmax,
                  RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiTrimCurve(RtInt nloops, RtInt ncurves[], RtInt order[], RtFloat knot[],
                   RtFloat min[], RtFloat max[], RtInt n[], RtFloat u[], RtFloat v[],
                   RtFloat w[]);
RtVoid RiSphere(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, ...);
RtVoid RiSphereV(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, RtInt n,
                 RtToken tokens[], RtPointer values[]);
RtVoid RiCone(RtFloat height, RtFloat radius, RtFloat thetamax, ...);
RtVoid RiConeV(RtFloat height, RtFloat radius, RtFloat thetamax, RtInt n,
               RtToken tokens[], RtPointer values[]);
RtVoid RiCylinder(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, ...);
RtVoid RiCylinderV(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, RtInt n,
                   RtToken tokens[], RtPointer values[]);
RtVoid RiHyperboloid(RtPoint point1, RtPoint point2, RtFloat thetamax, ...);
RtVoid RiHyperboloidV(RtPoint point1, RtPoint point2, RtFloat thetamax, RtInt n,
                      RtToken tokens[], RtPointer values[]);
RtVoid RiParaboloid(RtFloat rmax, RtFloat zmin, RtFloat zmax, RtFloat thetamax, ...);
RtVoid RiParaboloidV(RtFloat rmax, RtFloat zmin, RtFloat zmax, RtFloat thetamax, RtInt n,
                     RtToken tokens[], RtPointer values[]);
RtVoid RiDisk(RtFloat height, RtFloat radius, RtFloat thetamax, ...);
RtVoid RiDiskV(RtFloat height, RtFloat radius, RtFloat thetamax, RtInt n,
               RtToken tokens[], RtPointer values[]);
RtVoid RiTorus(RtFloat majorradius, RtFloat minorradius, RtFloat phimin, RtFloat phimax,
               RtFloat thetamax, ...);
RtVoid RiTorusV(RtFloat majorradius, RtFloat minorradius, RtFloat phimin, RtFloat phimax,
                RtFloat thetamax, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiPoints(RtInt npoints, ...);
RtVoid RiPointsV(RtInt npoints, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiCurves(RtToken type, RtInt ncurves, RtInt nvertices[], RtToken wrap, ...);
RtVoid RiCurvesV(RtToken type, RtInt ncurves, RtInt nvertices[], RtToken wrap, RtInt n,
                 RtToken tokens[], RtPointer values[]);
RtVoid RiSubdivisionMesh(RtToken scheme, RtInt nfaces, RtInt nvertices[],
                         RtInt vertices[], RtInt ntags, RtToken tags[], RtInt nargs[],
                         RtInt intargs[], RtFloat floatargs[], ...);
RtVoid RiSubdivisionMeshV(RtToken scheme, RtInt nfaces, RtInt nvertices[],
                          RtInt vertices[], RtInt ntags, RtToken tags[], RtInt nargs[],
                          RtInt intargs[], RtFloat floatargs[], RtInt n, RtToken tokens[],
                          RtPointer values[]);
RtVoid RiBlobby(RtInt nleaf, RtInt ncode, RtInt code[], RtInt nflt, RtFloat flt[],
                RtInt nstr, RtToken str[], ...);
RtVoid RiBlobbyV(RtInt nleaf, RtInt ncode, RtInt code[], RtInt nflt, RtFloat flt[],
                 RtInt nstr, RtToken str[], RtInt n, RtToken tokens[],
                 RtPointer values[]);
RtVoid RiProcedural(RtPointer data, RtBound bound, RtProcSubdivFunc subdivfunc,
                    RtProcFreeFunc freefunc);
RtVoid RiGeometry(RtToken type, ...);
RtVoid RiGeometryV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]);

/* Blocks: solids, retained objects, motion */
RtVoid RiSolidBegin(RtToken operation);
RtVoid RiSolidEnd(void);
RtObjectHandle RiObjectBegin(void);
RtVoid RiObjectEnd(void);
RtVoid RiObjectInstance(RtObjectHandle handle);
RtVoid RiMotionBegin(RtInt n, ...);
RtVoid RiMotionBeginV(RtInt n, RtFloat times[]);
RtVoid RiMotionEnd(void);

/* Textures */
RtVoid RiMakeTexture(RtString picturename, RtString texturename, RtToken swrap,
                     RtToken twrap, RtFilterFunc filterfunc, RtFloat swidth,
                     RtFloat twidth, ...);
RtVoid RiMakeTextureV(RtString picturename, RtString texturename, RtToken swrap,
                      RtToken twrap, RtFilterFunc filterfunc, RtFloat swidth,
                      RtFloat twidth, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiMakeLatLongEnvironment(RtString picturename, RtString texturename,
                                RtFilterFunc filterfunc, RtFloat swidth, RtFloat twidth,
                                ...);
RtVoid RiMakeLatLongEnvironmentV(RtString picturename, RtString texturename,
                                 RtFilterFunc filterfunc, RtFloat swidth, RtFloat twidth,
                                 RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiMakeCubeFaceEnvironment(RtString px, RtString nx, RtString py, RtString ny,
                                 RtString pz, RtString nz, RtString texturename,
                                 RtFloat fov, RtFilterFunc filterfunc, RtFloat swidth,
                                 RtFloat twidth, ...);
RtVoid RiMakeCubeFaceEnvironmentV(RtString px, RtString nx, RtString py, RtString ny,
                                  RtString pz, RtString nz, RtString texturename,
                                  RtFloat fov, RtFilterFunc filterfunc, RtFloat swidth,
                                  RtFloat twidth, RtInt n, RtToken tokens[],
                                  RtPointer values[]);
RtVoid RiMakeShadow(RtString picturename, RtString texturename, ...);
RtVoid RiMakeShadowV(RtString picturename, RtString texturename, RtInt n,
                     RtToken tokens[], RtPointer values[]);

/* Archives and errors */
RtVoid RiReadArchive(RtToken name, RtArchiveCallback callback, ...);
RtVoid RiReadArchiveV(RtToken name, RtArchiveCallback callback, RtInt n, RtToken tokens[],
                      RtPointer values[]);
RtVoid RiErrorHandler(RtErrorHandler handler);
/* A line in the RIB file RiBegin("f.rib") writes, printf-formatted: RI_COMMENT ("# ..."),
 * RI_STRUCTURE ("##...") or RI_VERBATIM (the text as it is). A render ignores comments;
 * verbatim RIB is an error there (it is not read). */
extern RtToken RI_COMMENT, RI_STRUCTURE, RI_VERBATIM;
RtVoid RiArchiveRecord(RtToken type, const char* format, ...);

/* PRMan's named attribute sets: RiResource("look", "attributes", "string operation",
 * &op, RI_NULL) with op "save" or "restore" ("string subset": "all", "shading",
 * "transform"); names given inside RiResourceBegin/RiResourceEnd end with the block. */
RtVoid RiResource(RtToken handle, RtToken type, ...);
RtVoid RiResourceV(RtToken handle, RtToken type, RtInt n, RtToken tokens[],
                   RtPointer values[]);
RtVoid RiResourceBegin(void);
RtVoid RiResourceEnd(void);

/* Conditional RIB (PRMan): the calls of the branches not taken are dropped. */
RtVoid RiIfBegin(RtString expression);
RtVoid RiElseIf(RtString expression);
RtVoid RiElse(void);
RtVoid RiIfEnd(void);

#ifdef __cplusplus
}
#endif

#endif
