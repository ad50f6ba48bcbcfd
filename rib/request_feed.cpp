// request_feed.cpp: requests given by a program, handed to the RIB reader one by one.
#include "request_feed.h"

#include "reader_impl.h"

namespace rib {

// Patches along one direction of a patch mesh (or segments of a curve) and the number of
// varying values along it. Returns false with `why` set when n does not fit the rules.
bool spanCount(bool cubic, bool periodic, long long n, int step, long long& patches,
               long long& varying, std::string& why) {
    if (!cubic) {
        if (n < (periodic ? 1 : 2)) {
            why = "needs at least " + std::to_string(periodic ? 1 : 2) + " vertices";
            return false;
        }
        patches = periodic ? n : n - 1;
        varying = n;
        return true;
    }
    if (periodic) {
        if (n < step || n % step != 0) {
            why = "periodic cubic needs a positive multiple of the basis step (" +
                  std::to_string(step) + ") vertices";
            return false;
        }
        patches = n / step;
        varying = patches;
        return true;
    }
    if (n < 4 || (n - 4) % step != 0) {
        why = "nonperiodic cubic needs 4 + k*" + std::to_string(step) + " vertices";
        return false;
    }
    patches = (n - 4) / step + 1;
    varying = patches + 1;
    return true;
}

bool wrapMode(const std::string& w, bool& periodic) {
    if (w == "periodic")
        periodic = true;
    else if (w == "nonperiodic")
        periodic = false;
    else
        return false;
    return true;
}

struct RequestFeed::Impl {
    ReadOptions options;  // (before the reader, which keeps a reference)
    Lexer lexer;
    detail::Reader reader;
    Impl(Target& target, Diagnostics& diag, const std::string& name,
         const ReadOptions& opts)
        : options(opts), lexer(name, diag), reader(lexer, target, diag, options) {}
};

RequestFeed::RequestFeed(Target& target, Diagnostics& diag, const std::string& name,
                         const ReadOptions& options)
    : m_impl(std::make_unique<Impl>(target, diag, name, options)) {}

RequestFeed::~RequestFeed() = default;

SourceLoc RequestFeed::at(int line) const {
    return m_impl->lexer.loc(line);
}

void RequestFeed::request(const std::string& name,
                          const std::vector<RequestValue>& values, int line) {
    m_impl->reader.request(name, values, at(line));
}

void RequestFeed::finish(int line) {
    m_impl->reader.finish(at(line));
}

bool RequestFeed::declaration(const std::string& token, ParamDecl& decl,
                              std::string& name) const {
    return m_impl->reader.lookUpParam(token, decl, name) ==
           detail::Reader::DeclLookup::Declared;
}

int RequestFeed::colorSamples() const {
    return m_impl->reader.colorSamples();
}
int RequestFeed::ustep() const {
    return m_impl->reader.ustep();
}
int RequestFeed::vstep() const {
    return m_impl->reader.vstep();
}

}  // namespace rib
