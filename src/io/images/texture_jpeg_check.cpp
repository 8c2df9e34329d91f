// A guard in front of stb_image's JPEG decoder. Debian's stb (2022-09)
// trusts a Huffman table's 16 code counts: counts summing to more than 256
// write past its 257-entry size table and 256-entry value table (found by
// fuzz_texture; stb added the check upstream later). This walks the file's
// segments the way stb reads them and refuses such a table before stb sees it.
#include <algorithm>
#include <cstdint>
#include <string>

#include "io/images/stb_guards.h"

namespace sombra {

namespace {

struct Reader {
    std::span<const unsigned char> bytes;
    std::size_t at = 0;
    bool done() const { return at >= bytes.size(); }
    int get8() { return done() ? -1 : bytes[at++]; }
    int get16() {
        const int hi = get8(), lo = get8();
        return hi < 0 || lo < 0 ? -1 : (hi << 8) | lo;
    }
};

bool is_restart(int m) { return m >= 0xd0 && m <= 0xd7; }

// The next marker's code from r.at, as stb finds it: the next 0xff, fill
// 0xff bytes skipped. In entropy-coded data (after a scan header) 0xff 0x00
// is a data byte and restart markers belong to the scan. -1 at the end.
int next_marker(Reader& r, bool in_scan) {
    for (;;) {
        int x = r.get8();
        while (x >= 0 && x != 0xff) x = r.get8();
        while (x == 0xff) x = r.get8();
        if (x < 0) return -1;
        if (in_scan && (x == 0x00 || is_restart(x))) continue;
        return x;
    }
}

}  // namespace

std::string jpeg_huffman_problem(std::span<const unsigned char> bytes) {
    Reader r{bytes, 0};
    while (r.get8() == 0xff) {
    }  // fill bytes, then the start-of-image marker (0xd8)
    bool in_scan = false;
    for (;;) {
        const int m = next_marker(r, in_scan);
        if (m < 0 || m == 0xd9) return {};  // the end: stb decides the rest
        in_scan = false;
        if (m == 0x01 || is_restart(m)) continue;  // markers without a length
        int length = r.get16();
        if (length < 0) return {};
        if (m != 0xc4) {
            r.at += static_cast<std::size_t>(length > 2 ? length - 2 : 0);
            in_scan = m == 0xda;
            continue;
        }
        // Define Huffman tables: stb reads table after table while the
        // segment's length says bytes are left, 17 + n bytes each.
        for (int left = length - 2; left > 0;) {
            const int q = r.get8();
            if (q < 0 || (q >> 4) > 1 || (q & 15) > 3) return {};  // stb refuses these itself
            int n = 0;
            // Past the file's end stb reads zeros, so a table cut short
            // still counts the bytes it has (found by fuzz_texture).
            for (int i = 0; i < 16; ++i) n += std::max(r.get8(), 0);
            if (n > 256)
                return "bad JPEG Huffman table: its code counts add up to " + std::to_string(n) + " (at most 256)";
            r.at += static_cast<std::size_t>(n);
            left -= 17 + n;
        }
    }
}

}  // namespace sombra
