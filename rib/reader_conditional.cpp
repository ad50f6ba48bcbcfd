// reader_conditional.cpp: conditional RIB (PRMan's IfBegin "expr", ElseIf "expr", Else,
// IfEnd). The requests of a branch not taken are read and dropped unchecked; conditionals
// nest, and a branch inside one not taken is not evaluated. Expressions (conditional.h)
// see every Attribute's and Option's first value as $group:name (an attribute where set
// in the attribute blocks open, else the option; the group defaults to "user") and
// $Frame. A target never sees the conditionals, only the requests of the branches taken.
#include "reader_impl.h"

namespace rib {
namespace detail {

bool Reader::conditional(const RequestInfo& info, const std::vector<Value>& vals,
                         const SourceLoc& loc) {
    if (info.req != Req::IfBegin && info.req != Req::ElseIf && info.req != Req::Else &&
        info.req != Req::IfEnd)
        return false;
    // (a branch not taken may hold anything: its conditions are not even parsed)
    const bool enclosingActive = info.req == Req::IfBegin
                                     ? branchActive()
                                     : !m_conds.empty() && m_conds.back().parentActive;
    Args args;
    if (enclosingActive && !parseArgs(info, vals, args, loc)) {
        if (info.req != Req::IfBegin) return true;
        args.strs.assign(1, "0");  // (a bad IfBegin still opens its block, not taken)
    }
    const std::string expr = args.strs.empty() ? std::string() : args.strs[0];
    switch (info.req) {
        case Req::IfBegin: {
            CondFrame f;
            f.loc = loc;
            f.parentActive = enclosingActive;
            f.active = enclosingActive && evaluate(expr, loc);
            f.taken = f.active;
            m_conds.push_back(f);
            break;
        }
        case Req::ElseIf:
        case Req::Else: {
            if (m_conds.empty()) {
                error(loc, std::string(info.name) + " without IfBegin");
                break;
            }
            CondFrame& f = m_conds.back();
            if (f.sawElse) {
                error(loc, std::string(info.name) + " after Else (IfBegin at " +
                               f.loc.str() + ")");
                f.active = false;
                break;
            }
            f.sawElse = info.req == Req::Else;
            f.active = f.parentActive && !f.taken &&
                       (info.req == Req::Else || evaluate(expr, loc));
            f.taken = f.taken || f.active;
            break;
        }
        default:  // IfEnd
            if (m_conds.empty())
                error(loc, "IfEnd without IfBegin");
            else
                m_conds.pop_back();
            break;
    }
    return true;
}

bool Reader::evaluate(const std::string& expr, const SourceLoc& loc) {
    bool result = false;
    std::string why;
    if (!evaluateCondition(
            expr, [this](const std::string& n) { return condVariable(n); }, result,
            why)) {
        error(loc, "condition \"" + expr + "\": " + why + " (taken as false)");
        return false;
    }
    return result;
}

std::optional<CondValue> Reader::condVariable(const std::string& name) const {
    if (name == "Frame") {
        if (!m_frame) return std::nullopt;
        CondValue v;
        v.isNumber = true;
        v.number = *m_frame;
        return v;
    }
    const std::string key = name.find(':') == std::string::npos ? "user:" + name : name;
    if (auto it = m_condAttributes->find(key); it != m_condAttributes->end())
        return it->second;
    if (auto it = m_condOptions.find(key); it != m_condOptions.end()) return it->second;
    return std::nullopt;
}

void Reader::noteCondValues(bool attribute, const std::string& group,
                            const ParamList& params) {
    if (params.params.empty()) return;
    if (attribute && m_condAttributes.use_count() > 1)  // (an open block keeps the old)
        m_condAttributes = std::make_shared<CondValues>(*m_condAttributes);
    CondValues& values = attribute ? *m_condAttributes : m_condOptions;
    for (const Param& p : params.params) {
        CondValue v;
        if (!p.strings.empty()) {
            v.text = p.strings[0];
        } else if (!p.ints.empty() || !p.floats.empty()) {
            v.isNumber = true;
            v.number = p.ints.empty() ? double(p.floats[0]) : double(p.ints[0]);
        } else {
            continue;
        }
        values[group + ":" + p.name] = v;
    }
}

}  // namespace detail
}  // namespace rib
