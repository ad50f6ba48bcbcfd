// ri_context.cpp: the Ri API's context, its parameter lists and its error handler.
#include "ri_context.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>
#include <set>

#include "ri_dynamic_load.h"
#include "ri_render_target.h"
#include "rib/writer.h"

namespace rd::ri {
namespace {

// Every context begun and not ended (RI 3.2 RiContext), and the current one (none after
// RiEnd until RiBegin or RiContext makes one current).
std::vector<std::unique_ptr<Context>> g_contexts;
Context* g_context = nullptr;
std::vector<Context*> g_captureSaved;  // the contexts current before each capture
RtErrorHandler g_handler = RiErrorPrint;

}  // namespace

rib::RequestValue number(double v) {
    rib::RequestValue r;
    r.nums.push_back(v);
    r.allInt = false;
    return r;
}

rib::RequestValue integer(long long v) {
    rib::RequestValue r;
    r.nums.push_back(double(v));
    return r;
}

rib::RequestValue string(RtString s) {
    rib::RequestValue r;
    r.isString = true;
    r.strs.emplace_back(s ? s : "");
    return r;
}

rib::RequestValue floats(const RtFloat* v, long long n) {
    rib::RequestValue r;
    r.array = true;
    r.allInt = false;
    if (v && n > 0) r.nums.assign(v, v + n);
    return r;
}

rib::RequestValue ints(const RtInt* v, long long n) {
    rib::RequestValue r;
    r.array = true;
    if (v && n > 0) r.nums.assign(v, v + n);
    return r;
}

rib::RequestValue strings(const RtString* v, long long n) {
    rib::RequestValue r;
    r.array = true;
    r.isString = true;
    for (long long i = 0; v && i < n; ++i) r.strs.emplace_back(v[i] ? v[i] : "");
    return r;
}

void Context::setHandler(RtErrorHandler handler) {
    g_handler = handler ? handler : RiErrorPrint;
}

void Context::report(int code, int severity, const std::string& message) {
    if (severity >= RIE_ERROR) RiLastError = code;
    g_handler(code, severity, message.c_str());
}

bool Context::active() {
    return g_context != nullptr;
}

Context* Context::current(const char* call) {
    if (!g_context) {
        report(RIE_NOTSTARTED, RIE_ERROR,
               std::string("Ri: error: ") + call + " before RiBegin: ignored");
        return nullptr;
    }
    ++g_context->m_call;
    return g_context;
}

// A new context, made current; the one current before stays, for RiContext.
void Context::begin(RtToken name) {
    RiLastError = RIE_NOERROR;
    enableDynamicLoad();  // (RiProcDynamicLoad in a render, or in RIB it reads)
    try {
        std::unique_ptr<Context> c(new Context(name));
        if (c->m_target) {
            g_contexts.push_back(std::move(c));
            g_context = g_contexts.back().get();
        }
    } catch (const std::exception& e) {
        report(RIE_SYSTEM, RIE_SEVERE, std::string("Ri: error: RiBegin: ") + e.what());
    }
}

void Context::end() {
    if (!g_context) {
        report(RIE_NOTSTARTED, RIE_ERROR, "Ri: error: RiEnd before RiBegin: ignored");
        return;
    }
    if (g_context->m_capture) {  // (endCapture ends it, once the object returns)
        report(RIE_ILLSTATE, RIE_ERROR,
               "Ri: error: RiEnd inside a DynamicLoad procedural's Subdivide: ignored");
        return;
    }
    try {
        g_context->m_feed->finish(++g_context->m_call);
    } catch (const std::exception& e) {
        report(RIE_SYSTEM, RIE_SEVERE, std::string("Ri: error: RiEnd: ") + e.what());
    }
    const Context* ended = g_context;
    g_context = nullptr;
    g_contexts.erase(std::find_if(
        g_contexts.begin(), g_contexts.end(),
        [&](const std::unique_ptr<Context>& c) { return c.get() == ended; }));
}

RtContextHandle Context::handle() {
    return g_context;
}

void Context::makeCurrent(RtContextHandle h) {
    if (g_context && g_context->m_capture) {
        report(
            RIE_ILLSTATE, RIE_ERROR,
            "Ri: error: RiContext inside a DynamicLoad procedural's Subdivide: ignored");
        return;
    }
    for (const std::unique_ptr<Context>& c : g_contexts)
        if (c.get() == h) {
            g_context = c.get();
            return;
        }
    report(RIE_BADHANDLE, RIE_ERROR,
           "Ri: error: RiContext: not a context RiGetContext gave (or it has ended): "
           "ignored");
}

// The object's calls come inside the world block the procedural is in: the capture's
// feed is put inside one (its WorldBegin left out of the RIB) so that it takes geometry.
void Context::beginCapture() {
    g_contexts.push_back(std::unique_ptr<Context>(new Context(nullptr, true)));
    g_captureSaved.push_back(g_context);
    g_context = g_contexts.back().get();
    g_context->send("WorldBegin", {});
    g_context->m_text.str("");
}

std::string Context::endCapture() {
    Context* capture = g_contexts.back().get();
    capture->send("WorldEnd", {});
    capture->m_feed.reset();
    capture->m_target.reset();  // (the writer ends its last line)
    std::string rib = capture->m_text.str();
    rib.erase(std::min(rib.size(), rib.rfind("WorldEnd")));
    g_contexts.pop_back();
    g_context = g_captureSaved.back();
    g_captureSaved.pop_back();
    return rib;
}

Context::Context(RtToken name, bool capture) : m_diag(nullptr, INT_MAX) {
    m_diag.setListener([this](bool isError, const std::string& message) {
        const int code = m_code ? m_code : isError ? RIE_CONSISTENCY : RIE_INCAPABLE;
        m_code = 0;
        report(code, isError ? RIE_ERROR : RIE_WARNING, message);
    });
    m_capture = capture;
    if (capture) {
        auto writer = std::make_unique<rib::RibWriter>(m_text);
        m_writer = writer.get();
        m_target = std::move(writer);
    } else if (name) {
        m_file.open(name, std::ios::binary);
        if (!m_file) {
            report(RIE_NOFILE, RIE_SEVERE,
                   std::string("Ri: error: RiBegin: cannot write \"") + name + "\"");
            return;
        }
        auto writer = std::make_unique<rib::RibWriter>(m_file);
        m_writer = writer.get();
        m_target = std::move(writer);
    } else {
        m_target = std::make_unique<RenderTarget>(m_diag, [](const std::string& why) {
            report(RIE_SYSTEM, RIE_SEVERE, "Ri: error: " + why);
        });
    }
    m_feed = std::make_unique<rib::RequestFeed>(*m_target, m_diag, "Ri");
}

Context::~Context() {
    m_feed.reset();
    m_target.reset();  // (a writer ends its last line)
    if (m_file.is_open()) {
        m_file.close();
        if (!m_file)
            report(RIE_SYSTEM, RIE_SEVERE,
                   "Ri: error: RiEnd: the RIB file was not written whole");
    }
}

void Context::record(const std::string& type, const std::string& text) {
    if (type != "comment" && type != "structure" && type != "verbatim") {
        error(RIE_BADTOKEN, "RiArchiveRecord: type \"" + type +
                                "\" is not comment, structure or verbatim");
        return;
    }
    if (m_writer)
        m_writer->record(type, text);
    else if (type == "verbatim")
        error(RIE_UNIMPLEMENT,
              "RiArchiveRecord: verbatim RIB is written to a RIB file; a "
              "render does not read it");
}

void Context::error(int code, const std::string& message) {
    m_code = code;
    m_diag.error(m_feed->at(m_call), message);
    m_code = 0;
}

void Context::send(const char* name, Values values, const ParamArgs& params,
                   const ClassCounts& counts) {
    // A shader call's first value is the shader's name (RiLightSource: then its handle).
    static const std::set<std::string> shaderCalls = {
        "Surface", "Displacement", "Atmosphere",  "Interior",       "Exterior",
        "Imager",  "Deformation",  "LightSource", "AreaLightSource"};
    // (a copy: `values` grows below)
    const std::string shader =
        shaderCalls.count(name) && !values.empty() && !values[0].strs.empty()
            ? values[0].strs[0]
            : std::string();
    const bool searchPath = std::string(name) == "Option" && !values.empty() &&
                            !values[0].strs.empty() && values[0].strs[0] == "searchpath";
    for (RtInt i = 0; i < params.n; ++i) {
        const RtToken token = params.tokens ? params.tokens[i] : nullptr;
        const RtPointer value = params.values ? params.values[i] : nullptr;
        if (!token) break;  // (RI_NULL ends a list)
        rib::ParamDecl decl;
        std::string bare, spelled = token;
        // Else, in a shader call, the shader's own (as if written inline)
        if (!shader.empty() && !m_feed->declaration(spelled, decl, bare))
            if (std::string found = m_shaderParams.declaration(shader, token);
                !found.empty())
                spelled = found + " " + token;
        if (!m_feed->declaration(spelled, decl, bare)) {
            error(RIE_BADTOKEN, std::string(name) + ": parameter \"" + token +
                                    "\" is not declared (RiDeclare it, or declare it "
                                    "inline: \"uniform float " +
                                    token + "\"); left out");
            continue;
        }
        if (!value) {
            error(RIE_MISSINGDATA, std::string(name) + ": parameter \"" + token +
                                       "\" has no values (a null pointer); left out");
            continue;
        }
        rib::Param probe;
        probe.type = decl.type;
        probe.colorComponents = m_feed->colorSamples();
        const long long n =
            std::max(0LL, counts.of(decl.storage)) * probe.components() * decl.arraySize;
        values.push_back(string(spelled.c_str()));
        if (decl.type == rib::ParamType::String)
            values.push_back(strings(static_cast<const RtString*>(value), n));
        else if (decl.type == rib::ParamType::Integer)
            values.push_back(ints(static_cast<const RtInt*>(value), n));
        else
            values.push_back(floats(static_cast<const RtFloat*>(value), n));
        if (searchPath && bare == "shader" && !values.back().strs.empty())
            m_shaderParams.setSearchPath(values.back().strs[0]);
    }
    // (no exception may leave a C call: a render's or the builder's failure is reported)
    try {
        m_feed->request(name, values, m_call);
    } catch (const std::bad_alloc&) {
        report(RIE_NOMEM, RIE_SEVERE,
               "Ri:" + std::to_string(m_call) + ": error: " + name +
                   ": out of memory on the host");
    } catch (const std::exception& e) {
        report(RIE_SYSTEM, RIE_SEVERE,
               "Ri:" + std::to_string(m_call) + ": error: " + name + ": " + e.what());
    }
}

}  // namespace rd::ri

RtInt RiLastError = RIE_NOERROR;

extern "C" {

RtVoid RiErrorIgnore(RtInt, RtInt, RtString) {}

RtVoid RiErrorPrint(RtInt, RtInt, RtString message) {
    std::fprintf(stderr, "%s\n", message ? message : "");
}

RtVoid RiErrorAbort(RtInt, RtInt severity, RtString message) {
    RiErrorPrint(0, severity, message);
    if (severity >= RIE_ERROR) std::exit(1);
}

}  // extern "C"
