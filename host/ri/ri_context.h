// ri_context.h: the state behind the Ri C functions (ri.h) between RiBegin and RiEnd: the
// target the calls go to (the renderer, or a RIB file), the RequestFeed that checks them
// as the RIB reader checks a file, the light and object handles given out, and the error
// handler. The C functions turn their arguments into request values here: a parameter
// list's values are counted from each token's declaration and the primitive's classes
// (RI 3.2 section 5: uniform, varying, vertex, facevarying), since C passes bare
// pointers.
#pragma once
#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "ri.h"
#include "ri_shader_params.h"
#include "rib/request_feed.h"
#include "rib/writer.h"

namespace rd::ri {

using rib::ClassCounts;

using Values = std::vector<rib::RequestValue>;
rib::RequestValue number(double v);
rib::RequestValue integer(long long v);
rib::RequestValue string(RtString s);
rib::RequestValue floats(const RtFloat* v, long long n);
rib::RequestValue ints(const RtInt* v, long long n);
rib::RequestValue strings(const RtString* v, long long n);

// A call's (token, value) pairs: those of an RiFooV call, or collected from RiFoo's
// variable arguments up to RI_NULL.
struct ParamArgs {
    RtInt n = 0;
    const RtToken* tokens = nullptr;
    const RtPointer* values = nullptr;
};

class Context {
public:
    // The context between RiBegin and RiEnd; nullptr outside (the call is then reported
    // as RIE_NOTSTARTED and ignored).
    static Context* current(const char* call);
    // Whether RiBegin has begun a context (nothing is reported or counted).
    static bool active();
    static void begin(RtToken name);
    static void end();
    // RiGetContext (nullptr: none current) and RiContext.
    static RtContextHandle handle();
    static void makeCurrent(RtContextHandle h);
    // While a DynamicLoad object runs: a context that writes its calls as RIB into
    // memory is current (beginCapture); endCapture ends it, returns that RIB and makes
    // current again the context that was (ri_dynamic_load.h).
    static void beginCapture();
    static std::string endCapture();

    // Request `name` with its positional `values` and the parameters, counted by
    // `counts`.
    void send(const char* name, Values values, const ParamArgs& params = {},
              const ClassCounts& counts = {});
    // An error of the API's own at the current call.
    void error(int code, const std::string& message);
    // RiArchiveRecord: a line of the RIB file written (comments ignored by a render).
    void record(const std::string& type, const std::string& text);
    rib::RequestFeed& feed() { return *m_feed; }
    // RiTransformPoints through the target (false: it keeps no state, or cannot).
    bool transformPoints(const std::string& from, const std::string& to, float* xyz,
                         int n) {
        return m_target->transformPoints(from, to, xyz, n);
    }
    uintptr_t nextLight() { return ++m_lights; }
    uintptr_t nextObject() { return ++m_objects; }

    static void setHandler(RtErrorHandler handler);
    // Reports to the handler in force (also outside RiBegin/RiEnd).
    static void report(int code, int severity, const std::string& message);

    ~Context();

private:
    explicit Context(RtToken name, bool capture = false);
    rib::Diagnostics m_diag;
    std::ofstream m_file;  // RiBegin("file.rib")
    std::ostringstream m_text;  // beginCapture's RIB
    bool m_capture = false;     // a DynamicLoad object's calls: RiEnd may not end it
    std::unique_ptr<rib::Target> m_target;
    rib::RibWriter* m_writer = nullptr;  // m_target, when it writes RIB
    std::unique_ptr<rib::RequestFeed> m_feed;
    ShaderParams m_shaderParams;  // shaders' own parameter declarations
    uintptr_t m_lights = 0, m_objects = 0;
    int m_call = 0;  // the current call's number since RiBegin (its messages' "line")
    int m_code = 0;  // the code of the next message the diagnostics report
};

}  // namespace rd::ri
