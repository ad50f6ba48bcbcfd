// reader_archive.cpp: archives. ReadArchive reads another RIB file (found next to the
// file being read, then along the archive search path) through a fresh lexer, so it may
// be binary or gzip-compressed whatever its parent is; inline archives (ArchiveBegin
// "name" ... ArchiveEnd) are kept as tokens and replayed by ReadArchive "name". Nesting
// is limited so an archive that reads itself is an error, not a stack overflow.
#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "reader_impl.h"
#include "run_program.h"

namespace rib {
namespace detail {

namespace {

bool fileExists(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    std::fclose(f);
    return true;
}

}  // namespace

void Reader::noteOption(const std::string& name, const ParamList& params) {
    if (name != "searchpath") return;
    for (const char* key : {"archive", "resource"}) {
        const Param* p = params.find(key);
        if (!p || p->strings.empty()) continue;
        std::string path = p->strings[0], out;
        for (char c : path) {
            if (c == '&')
                out += m_archivePath;
            else
                out += c;
        }
        m_archivePath = out;
    }
}

std::string Reader::resolveArchive(const std::string& name) const {
    if (name.empty()) return std::string();
    if (name[0] == '/') return fileExists(name) ? name : std::string();
    if (fileExists(m_dir + name)) return m_dir + name;
    size_t start = 0;
    while (start <= m_archivePath.size()) {
        size_t end = m_archivePath.find(':', start);
        if (end == std::string::npos) end = m_archivePath.size();
        std::string dir = m_archivePath.substr(start, end - start);
        if (!dir.empty()) {
            std::string path = dir + (dir.back() == '/' ? "" : "/") + name;
            if (fileExists(path)) return path;
        }
        start = end + 1;
    }
    return std::string();
}

// A DynamicLoad object's path: as named when that exists, else beside the reading file,
// then on the archive search path, each also with ".so" added (PRMan's convention).
std::string Reader::resolveDynamicObject(const std::string& name) const {
    for (const std::string& n : {name, name + ".so"}) {
        if (fileExists(n)) return n;
        if (std::string found = resolveArchive(n); !found.empty()) return found;
    }
    return name;  // (dlopen's own search: LD_LIBRARY_PATH, the system's)
}

void Reader::expandProcedural(const std::string& name, const std::vector<std::string>& args,
                              const SourceLoc& loc) {
    std::string file = args[0];
    std::string temp;
    if (name == "RunProgram" || name == "DynamicLoad") {
        // RI protocol: the program reads "detail datablock" and answers with RIB ended
        // by a 0377 byte (run_program.h: bounded in time and size); a DynamicLoad object
        // is run in this process and its Ri calls are captured as RIB. One run per
        // request; the answer goes through a temporary file so it is read like any
        // archive (and may itself be gzip or binary).
        std::string text, why;
        const bool ran =
            name == "RunProgram"
                ? runProgram(args[0], "1000000 " + args[1],
                             {m_opts.runProgramSeconds, m_opts.runProgramMaxBytes}, &text,
                             &why)
                : dynamicLoader()(resolveDynamicObject(args[0]), args[1], 1000000.0f,
                                  &text, &why);
        if (!ran) {
            error(loc, name + " \"" + args[0] + "\": " + why);
            return;
        }
        char tmpl[] = "/tmp/raydrive-runprogram-XXXXXX";
        int fd = mkstemp(tmpl);
        if (fd < 0) {
            error(loc, name + ": cannot create a temporary file");
            return;
        }
        temp = tmpl;
        bool written = true;
        for (size_t done = 0; written && done < text.size();) {
            const ssize_t n = write(fd, text.data() + done, text.size() - done);
            written = n > 0;
            done += written ? size_t(n) : 0;
        }
        close(fd);
        if (!written) {
            error(loc, name + ": cannot write a temporary file");
            std::remove(temp.c_str());
            return;
        }
        file = temp;
    }
    m_target.attributeBegin(loc);
    readArchive(file, ParamList(), loc);
    m_target.attributeEnd(loc);
    if (!temp.empty()) std::remove(temp.c_str());
}

void Reader::readArchive(const std::string& name, const ParamList& params,
                         const SourceLoc& loc) {
    (void)params;
    if (m_archiveDepth >= m_opts.maxArchiveDepth) {
        error(loc, "ReadArchive \"" + name + "\": archives nested more than " +
                       std::to_string(m_opts.maxArchiveDepth) +
                       " deep (does an archive read itself?)");
        return;
    }
    // Everything below is restored when the archive ends.
    Token pending = m_pending;
    bool havePending = m_havePending;
    m_havePending = false;
    auto hold = m_replayHold;
    const std::vector<Token>* replay = m_replay;
    size_t replayPos = m_replayPos;
    std::string replayFile = m_replayFile;
    Lexer* lex = m_lex;
    std::string dir = m_dir;
    int lastLine = m_lastLine;
    ++m_archiveDepth;

    auto inl = m_inlineArchives.find(name);
    if (inl != m_inlineArchives.end()) {
        m_replayHold = inl->second;
        m_replay = &m_replayHold->tokens;
        m_replayPos = 0;
        m_replayFile = m_replayHold->file;
        readStream();
    } else {
        std::string path = resolveArchive(name);
        gzFile file = path.empty() ? nullptr : gzopen(path.c_str(), "rb");
        if (!file) {
            error(loc, "ReadArchive: cannot open \"" + name + "\"" +
                           (path.empty() ? std::string(" (not found)")
                                         : ": " + std::string(std::strerror(errno))));
        } else {
            Lexer archiveLex(path, m_diag);
            archiveLex.setFile(file);
            m_lex = &archiveLex;
            m_replay = nullptr;
            size_t slash = path.rfind('/');
            m_dir = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
            readStream();
            gzclose(file);
        }
    }

    --m_archiveDepth;
    m_pending = pending;
    m_havePending = havePending;
    m_replayHold = hold;
    m_replay = replay;
    m_replayPos = replayPos;
    m_replayFile = replayFile;
    m_lex = lex;
    m_dir = dir;
    m_lastLine = lastLine;
}

void Reader::recordInlineArchive(const std::string& name, const SourceLoc& loc) {
    auto archive = std::make_shared<InlineArchive>();
    archive->file = loc.file;
    int depth = 0;
    bool tooBig = false;
    while (!m_diag.tooManyErrors()) {
        Token t = nextToken();
        if (t.kind == TokenKind::Eof) {
            error(loc, "ArchiveBegin \"" + name + "\" never closed");
            return;
        }
        if (t.kind == TokenKind::Word) {
            if (t.text == "ArchiveBegin") {
                ++depth;
            } else if (t.text == "ArchiveEnd") {
                if (depth == 0) break;
                --depth;
            }
        }
        if (archive->tokens.size() >= m_opts.maxArrayValues) {
            if (!tooBig)
                error(loc, "ArchiveBegin \"" + name + "\" is too large (more than " +
                               std::to_string(m_opts.maxArrayValues) + " tokens)");
            tooBig = true;
            continue;
        }
        archive->tokens.push_back(std::move(t));
    }
    if (tooBig) return;
    m_inlineArchives[name] = std::move(archive);
}

}  // namespace detail
}  // namespace rib
