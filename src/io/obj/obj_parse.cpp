// Two passes over chunks of whole lines, both in parallel: the first counts
// each chunk's lines, `v` and `vn`, so that the second knows where its
// vertices go, which line it starts at, and what a negative (relative)
// index counts back from. Nothing is allocated per line.
#include "io/obj/obj_parse.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "scene/mesh.h"

namespace sombra {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }
bool ends_line(char c) { return c == '\n' || c == '\r'; }

// The first \n or \r at or after p, or `end`. memchr in windows, so that a
// file whose lines end in \r alone stays linear.
const char* find_line_end(const char* p, const char* end) {
    while (p != end) {
        if (ends_line(*p)) return p;
        const char* window = p + std::min<std::ptrdiff_t>(end - p, 4096);
        const char* nl = static_cast<const char*>(std::memchr(p, '\n', std::size_t(window - p)));
        const char* cr = static_cast<const char*>(std::memchr(p, '\r', std::size_t((nl ? nl : window) - p)));
        if (cr) return cr;
        if (nl) return nl;
        p = window;
    }
    return end;
}

// The start of the line after the one ending at `line_end` (\r\n counts once).
const char* next_line(const char* line_end, const char* end) {
    if (line_end == end) return end;
    return line_end + (*line_end == '\r' && line_end + 1 != end && line_end[1] == '\n' ? 2 : 1);
}

// Where a line's content ends: its line end or a NUL before it (tinyobjloader
// read each line as a C string).
const char* find_content_end(const char* p, const char* end) {
    while (p != end && *p != '\n' && *p != '\r' && *p != '\0') ++p;
    return p;
}

enum class LineKind { Other, Vertex, Normal, TexCoord, Face, Polyline, Points, Usemtl, Mtllib };

// The line's kind from its keyword `k` (after leading blanks). `vw` (skin
// weights) and everything unknown is Other; `usemtl` needs no blank after it.
LineKind classify(const char* k, const char* end) {
    const std::size_t n = std::size_t(end - k);
    auto at = [&](std::size_t i) { return i < n ? k[i] : '\0'; };
    switch (at(0)) {
        case 'v':
            if (is_blank(at(1))) return LineKind::Vertex;
            if (at(1) == 'n' && is_blank(at(2))) return LineKind::Normal;
            if (at(1) == 't' && is_blank(at(2))) return LineKind::TexCoord;
            return LineKind::Other;
        case 'f': return is_blank(at(1)) ? LineKind::Face : LineKind::Other;
        case 'l': return is_blank(at(1)) ? LineKind::Polyline : LineKind::Other;
        case 'p': return is_blank(at(1)) ? LineKind::Points : LineKind::Other;
        case 'u': return n >= 6 && std::memcmp(k, "usemtl", 6) == 0 ? LineKind::Usemtl : LineKind::Other;
        case 'm':
            return n >= 7 && std::memcmp(k, "mtllib", 6) == 0 && is_blank(k[6]) ? LineKind::Mtllib : LineKind::Other;
        default: return LineKind::Other;
    }
}

const char* skip_blanks(const char* p, const char* end) {
    while (p != end && is_blank(*p)) ++p;
    return p;
}

// Numbers contain digits, signs, '.', 'e'; nan, inf and MSVC's 1.#IND / 1.#INF do not.
bool spells_non_finite(const char* p, const char* end) {
    for (; p != end; ++p) {
        if (*p == 'n' || *p == 'N' || *p == 'i' || *p == 'I' || *p == '#') return true;
    }
    return false;
}

// x, y, z from the first three blank-separated tokens after q, 0 where one
// is missing or no number; `non_finite` when one is spelled nan or inf.
// Returns where reading stopped (at most the line's end).
const char* read_xyz(const char* q, const char* end, Vec3& xyz, bool& non_finite) {
    non_finite = false;
    bool over = false;  // the line's content has ended: the rest are missing
    for (int k = 0; k < 3; ++k) {
        xyz[k] = 0;
        if (over) continue;
        q = skip_blanks(q, end);
        const char* token = q;
        while (q != end && !is_blank(*q) && !ends_line(*q) && *q != '\0') ++q;
        over = q == end || !is_blank(*q);
        const char* read = read_obj_real(token, q, xyz[k]);
        non_finite |= spells_non_finite(read ? read : token, q);
    }
    return q;
}

std::string_view trimmed(const char* p, const char* end) {
    p = skip_blanks(p, end);
    while (end != p && is_blank(end[-1])) --end;
    return {p, std::size_t(end - p)};
}

// Splits [begin, end) into chunks of about `chunk_bytes`, each starting at a line start.
std::vector<const char*> split_at_lines(const char* begin, const char* end, std::size_t chunk_bytes) {
    std::vector<const char*> bounds{begin};
    const std::size_t size = std::size_t(end - begin);
    for (std::size_t target = chunk_bytes; target < size; target += chunk_bytes) {
        const char* b = std::max(begin + target, bounds.back());
        if (b == bounds.back()) continue;  // inside a line that an earlier chunk ends after
        const bool line_start = b[-1] == '\n' || (b[-1] == '\r' && *b != '\n');
        if (!line_start) b = next_line(find_line_end(b, end), end);
        if (b == end) break;
        bounds.push_back(b);
    }
    bounds.push_back(end);
    return bounds;
}

struct ChunkCounts {
    std::size_t lines = 0;
    std::int64_t positions = 0, texcoords = 0, normals = 0;
};

ChunkCounts count_chunk(const char* p, const char* end) {
    ChunkCounts counts;
    while (p != end) {
        ++counts.lines;
        const char* k = skip_blanks(p, end);
        switch (classify(k, end)) {
            case LineKind::Vertex: ++counts.positions; break;
            case LineKind::Normal: ++counts.normals; break;
            case LineKind::TexCoord: ++counts.texcoords; break;
            default: break;
        }
        p = next_line(find_line_end(k, end), end);
    }
    return counts;
}

// The first problem of one kind in a chunk; line 0: none.
struct Problem {
    std::size_t line = 0;
    ObjLineProblem problem;
};

struct Chunk {
    const char* begin = nullptr;
    const char* end = nullptr;
    ChunkCounts counts;
    ChunkCounts before;  // sums over the chunks before this one
    ObjFaceBlock faces;
    std::vector<ObjDirective> directives;  // `face` counts this chunk's faces only, until merged
    std::size_t small_faces = 0, bad_normal_refs = 0;
    Problem index_problem, unreadable, out_of_range;  // reported in this order of precedence
};

struct Totals {
    std::int64_t positions, normals, texcoords;
};

void parse_chunk(Chunk& chunk, const Totals& totals, std::vector<Vec3>& positions, std::vector<Vec3>& normals,
                 std::vector<Vec2>& texcoords) {
    const char* const end = chunk.end;
    std::size_t line = chunk.before.lines;
    ObjIndexCounts seen{chunk.before.positions, chunk.before.normals, chunk.before.texcoords};
    std::vector<ObjCorner> corners;
    ObjLineProblem problem;
    ObjFaceBlock& out = chunk.faces;
    // About what a chunk of faces holds ("f 1 2 3\n" is 8 bytes a corner or more), capped.
    const std::size_t corner_guess = std::min<std::size_t>(std::size_t(end - chunk.begin) / 8, 1 << 17);
    out.positions.reserve(corner_guess);
    out.normals.reserve(corner_guess);
    if (totals.texcoords > 0) out.texcoords.reserve(corner_guess);
    out.ends.reserve(corner_guess / 3);
    for (const char* p = chunk.begin; p != end;) {
        ++line;
        const char* k = skip_blanks(p, end);
        const LineKind kind = classify(k, end);
        const char* stop = k;  // where this line's reading stopped
        if (kind == LineKind::Vertex || kind == LineKind::Normal) {
            Vec3 xyz;
            bool non_finite = false;
            stop = read_xyz(k + (kind == LineKind::Vertex ? 2 : 3), end, xyz, non_finite);
            if (kind == LineKind::Normal) {
                normals[std::size_t(seen.normals++)] = xyz;
            } else {
                positions[std::size_t(seen.positions++)] =
                    non_finite ? Vec3(std::numeric_limits<float>::quiet_NaN()) : xyz;
            }
        } else if (kind == LineKind::TexCoord) {
            Vec3 uvw;
            bool non_finite = false;
            stop = read_xyz(k + 3, end, uvw, non_finite);
            texcoords[std::size_t(seen.texcoords++)] = Vec2{uvw.x, uvw.y};
        } else if (kind != LineKind::Other) {
            const char* content_end = find_content_end(k, end);
            stop = content_end;
            if (kind == LineKind::Face) {
                const ObjLineStatus status = read_obj_face(k + 2, content_end, seen, corners, problem);
                if (status == ObjLineStatus::IndexProblem) {
                    // The earliest of these anywhere is the error: nothing after it matters.
                    chunk.index_problem = {line, std::move(problem)};
                    return;
                }
                if (status == ObjLineStatus::Unreadable) {
                    if (chunk.unreadable.line == 0) chunk.unreadable = {line, std::move(problem)};
                } else if (corners.size() < 3) {
                    ++chunk.small_faces;
                } else {
                    for (const ObjCorner& c : corners) {
                        if ((c.position < 0 || c.position >= totals.positions) && chunk.out_of_range.line == 0) {
                            chunk.out_of_range = {line,
                                                  {"face index " + std::to_string(c.position + 1) +
                                                   " out of range (the file has " + std::to_string(totals.positions) +
                                                   " vertices)"}};
                        }
                        out.positions.push_back(static_cast<std::uint32_t>(c.position));
                        const bool has_normal = c.normal >= 0 && c.normal < totals.normals;
                        chunk.bad_normal_refs += !has_normal && c.normal != -1;
                        out.normals.push_back(has_normal ? static_cast<std::uint32_t>(c.normal) : kNoNormal);
                        // A texture coordinate the file does not define is dropped silently.
                        const bool has_uv = c.texcoord >= 0 && c.texcoord < totals.texcoords;
                        if (totals.texcoords > 0)
                            out.texcoords.push_back(has_uv ? static_cast<std::uint32_t>(c.texcoord) : kNoUv);
                    }
                    out.ends.push_back(static_cast<std::uint32_t>(out.positions.size()));
                }
            } else if (kind == LineKind::Polyline || kind == LineKind::Points) {
                if (!obj_index_line_readable(k + 2, content_end) && chunk.unreadable.line == 0) {
                    chunk.unreadable = {line,
                                        {std::string(kind == LineKind::Polyline ? "`l`" : "`p`") +
                                         " line: an index is 0 or not a number"}};
                }
            } else {
                const bool usemtl = kind == LineKind::Usemtl;
                chunk.directives.push_back({usemtl ? ObjDirective::Kind::Usemtl : ObjDirective::Kind::Mtllib, line,
                                            out.ends.size(),
                                            usemtl ? trimmed(k + 6, content_end)
                                                   : std::string_view(k + 7, std::size_t(content_end - (k + 7)))});
            }
        }
        p = next_line(find_line_end(stop, end), end);
    }
}

}  // namespace

ObjGeometry parse_obj(std::string_view text, const std::string& where, std::size_t chunk_bytes) {
    const std::vector<const char*> bounds =
        split_at_lines(text.data(), text.data() + text.size(), std::max<std::size_t>(chunk_bytes, 1));
    std::vector<Chunk> chunks(bounds.size() - 1);
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        chunks[i].begin = bounds[i];
        chunks[i].end = bounds[i + 1];
    }
    tbb::parallel_for(std::size_t(0), chunks.size(),
                      [&](std::size_t i) { chunks[i].counts = count_chunk(chunks[i].begin, chunks[i].end); });
    ChunkCounts sum;
    for (Chunk& chunk : chunks) {
        chunk.before = sum;
        sum.lines += chunk.counts.lines;
        sum.positions += chunk.counts.positions;
        sum.texcoords += chunk.counts.texcoords;
        sum.normals += chunk.counts.normals;
    }

    ObjGeometry geometry;
    geometry.positions.resize(std::size_t(sum.positions));
    geometry.normals.resize(std::size_t(sum.normals));
    geometry.texcoords.resize(std::size_t(sum.texcoords));
    const Totals totals{sum.positions, sum.normals, sum.texcoords};
    tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t i) {
        parse_chunk(chunks[i], totals, geometry.positions, geometry.normals, geometry.texcoords);
    });

    const std::int64_t part_totals[3] = {sum.positions, sum.texcoords, sum.normals};
    for (Problem Chunk::*kind : {&Chunk::index_problem, &Chunk::unreadable, &Chunk::out_of_range}) {
        for (const Chunk& chunk : chunks) {
            const Problem& found = chunk.*kind;
            if (found.line == 0) continue;
            std::string what = found.problem.what;
            if (found.problem.needs_total)
                what += obj_total_suffix(found.problem.part, part_totals[found.problem.part]);
            throw Error(where + ":" + std::to_string(found.line), what);
        }
    }

    std::size_t faces_before = 0;
    for (Chunk& chunk : chunks) {
        for (ObjDirective& d : chunk.directives) {
            d.face += faces_before;
            geometry.directives.push_back(d);
        }
        faces_before += chunk.faces.ends.size();
        geometry.small_faces += chunk.small_faces;
        geometry.bad_normal_refs += chunk.bad_normal_refs;
        geometry.faces.push_back(std::move(chunk.faces));
    }
    return geometry;
}

}  // namespace sombra
