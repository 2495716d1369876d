#!/usr/bin/env python3
"""Generates src/sh/rotation_x90_table.h: the SH rotation blocks of Rx(+90 degrees) for bands
0..kMaxFastBands-1, as the constant sparse tables of the float zxzxz rotation (src/sh/rotation.cpp).

Usage: scripts/gen_sh_rotation.py [output path]   (default: src/sh/rotation_x90_table.h)

The blocks come from the Ivanic-Ruedenberg recursion (J. Phys. Chem. 100, 6342 (1996), errata
J. Phys. Chem. A 102, 9099 (1998)) evaluated with mpmath at 50 significant digits, in prt's basis
(real, orthonormal, Condon-Shortley phase, index l(l+1)+m; see src/sh/basis.h), then rounded once to
float. This is an implementation independent of the double recursion in rotation.cpp; the tests
compare the two.

Structure used: in band l, entry (m, n) of the Rx(90) block is non-zero only when m and n fall in
matching classes, a class being "sign of m (m >= 0 or m < 0) and parity of m". Each band is thus
four dense sub-blocks whose rows (and columns) are arithmetic runs of m with step +2 or -2; about a
quarter of the block's entries.
"""
import sys
from pathlib import Path

import mpmath as mp

mp.mp.dps = 50
FAST_BANDS = 16  # kMaxFastBands in src/sh/basis.h


def rotation_blocks(r, bands):
    """Blocks B^l[(m, n)] (Condon-Shortley phase) of the active rotation r (3x3, column vectors)."""
    x, y, z = 0, 1, 2
    axis = {-1: y, 0: z, 1: x}
    # Without the Condon-Shortley phase, band 1 is r with rows and columns ordered (y, z, x).
    r1 = {(i, j): r[axis[i]][axis[j]] for i in (-1, 0, 1) for j in (-1, 0, 1)}
    blocks = [{(0, 0): mp.mpf(1)}, r1]
    for l in range(2, bands):
        prev = blocks[l - 1]

        def p(i, a, b):
            if b == l:
                return r1[(i, 1)] * prev[(a, l - 1)] - r1[(i, -1)] * prev[(a, -l + 1)]
            if b == -l:
                return r1[(i, 1)] * prev[(a, -l + 1)] + r1[(i, -1)] * prev[(a, l - 1)]
            return r1[(i, 0)] * prev[(a, b)]

        block = {}
        for m in range(-l, l + 1):
            for n in range(-l, l + 1):
                d = 1 if m == 0 else 0
                den = mp.mpf((l + n) * (l - n) if abs(n) < l else (2 * l) * (2 * l - 1))
                u = mp.sqrt((l + m) * (l - m) / den)
                v = mp.sqrt((1 + d) * (l + abs(m) - 1) * (l + abs(m)) / den) * (1 - 2 * d) / 2
                w = -mp.sqrt((l - abs(m) - 1) * (l - abs(m)) / den) * (1 - d) / 2
                value = mp.mpf(0)
                if u != 0:
                    value += u * p(0, m, n)
                if v != 0:
                    if m == 0:
                        big_v = p(1, 1, n) + p(-1, -1, n)
                    elif m > 0:
                        big_v = p(1, m - 1, n) * mp.sqrt(1 + (m == 1)) - p(-1, -m + 1, n) * (1 - (m == 1))
                    else:
                        big_v = p(1, m + 1, n) * (1 - (m == -1)) + p(-1, -m - 1, n) * mp.sqrt(1 + (m == -1))
                    value += v * big_v
                if w != 0:
                    if m > 0:
                        big_w = p(1, m + 1, n) + p(-1, -m - 1, n)
                    else:
                        big_w = p(1, m - 1, n) - p(-1, -m + 1, n)
                    value += w * big_w
                block[(m, n)] = value
        blocks.append(block)
    # The Condon-Shortley phase multiplies Y_lm by (-1)^m: conjugate every block by diag((-1)^m).
    return [{(m, n): v * (-1) ** ((m + n) % 2) for (m, n), v in b.items()} for b in blocks]


def classes(l):
    """The four runs of m in band l: (start, step, count) for m>=0 even, m>0 odd, m<0 even, m<0 odd."""
    return [(0, 2, l // 2 + 1), (1, 2, (l + 1) // 2), (-2, -2, l // 2), (-1, -2, (l + 1) // 2)]


def run(start, step, count):
    return [start + step * k for k in range(count)]


def to_float32(value):
    import struct
    return struct.unpack("f", struct.pack("f", float(value)))[0]


def float_literal(value):
    text = f"{value:.9g}"
    if "." not in text and "e" not in text:
        text += ".0"
    return text + "f"


def main():
    out_path = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "src/sh/rotation_x90_table.h"
    one, zero = mp.mpf(1), mp.mpf(0)
    rx90 = [[one, zero, zero], [zero, zero, -one], [zero, one, zero]]
    blocks = rotation_blocks(rx90, FAST_BANDS)
    tiny = mp.mpf(10) ** -40
    descriptors, values = [], []
    for l, block in enumerate(blocks):
        row_descs = []
        for row_class in classes(l):
            rows = run(*row_class)
            if not rows:
                row_descs.append(None)
                continue
            # The column class is the one holding the non-zeros of the first row.
            col_class = next(c for c in classes(l) if c[2] > 0 and any(abs(block[(rows[0], n)]) > tiny for n in run(*c)))
            cols = run(*col_class)
            row_descs.append((row_class, col_class, len(values)))
            for m in rows:
                for n in cols:
                    values.append(to_float32(block[(m, n)]))
        # Every entry outside the sub-blocks must vanish, or the structure assumption is wrong.
        for (m, n), v in block.items():
            inside = any(d is not None and m in run(*d[0]) and n in run(*d[1]) for d in row_descs)
            if not inside and abs(v) > tiny:
                raise SystemExit(f"band {l}: entry ({m}, {n}) = {v} outside the sub-blocks")
        descriptors.append(row_descs)

    lines = [
        "#pragma once",
        "// GENERATED by scripts/gen_sh_rotation.py: do not edit. The SH rotation blocks of Rx(+90 degrees)",
        "// (active, column vectors; prt's real orthonormal basis with the Condon-Shortley phase) for bands",
        "// 0..kX90Bands-1, as four dense sub-blocks per band. Sub-block s of band l maps the input run",
        "// n = col_start + k * col_step (k < cols) to the output run m = row_start + i * row_step (i < rows):",
        "//   out[index(l, m_i)] = sum_k kX90Values[offset + i * cols + k] * in[index(l, n_k)].",
        "// Runs are the classes (m >= 0 even, m > 0 odd, m < 0 even, m < 0 odd); entries outside the",
        "// sub-blocks are exactly zero. Values: Ivanic-Ruedenberg in 50-digit arithmetic, rounded to float.",
        "#include <cstdint>",
        "",
        "namespace prt::sh::detail {",
        "",
        "struct X90SubBlock {",
        "  std::int8_t row_start, row_step, col_start, col_step;",
        "  std::uint8_t rows, cols;",
        "  std::uint16_t offset;  // into kX90Values; rows * cols values, row-major",
        "};",
        "",
        f"inline constexpr int kX90Bands = {FAST_BANDS};",
        "",
        "inline constexpr X90SubBlock kX90SubBlocks[kX90Bands][4] = {",
    ]
    for l, row_descs in enumerate(descriptors):
        parts = []
        for d in row_descs:
            if d is None:
                parts.append("{0, 0, 0, 0, 0, 0, 0}")
            else:
                (rs, rstep, rc), (cs, cstep, cc), off = d
                parts.append(f"{{{rs}, {rstep}, {cs}, {cstep}, {rc}, {cc}, {off}}}")
        lines.append(f"    {{{', '.join(parts)}}},  // l = {l}")
    lines.append("};")
    lines.append("")
    lines.append(f"inline constexpr float kX90Values[{len(values)}] = {{")
    per_line = 6
    for i in range(0, len(values), per_line):
        chunk = ", ".join(float_literal(v) for v in values[i:i + per_line])
        lines.append(f"    {chunk},")
    lines.append("};")
    lines.append("")
    lines.append("}  // namespace prt::sh::detail")
    out_path.write_text("\n".join(lines) + "\n")
    print(f"wrote {out_path}: {len(values)} values for {FAST_BANDS} bands")


if __name__ == "__main__":
    main()
