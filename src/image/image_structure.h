#pragma once
// The container structure of PNG, OpenEXR and BMP files, checked by prt before OpenImageIO sees the
// file: every length a file declares must lie inside the file, and OpenEXR data windows and BMP sides
// must be within prt's image limits (backend.h), before a codec allocates or reads by them.
//
// Why: OpenImageIO 2.4's PNG reader reports a short read (a chunk that claims more bytes than the file
// holds) by passing a temporary std::string's text to libpng's png_error, whose longjmp skips that
// string's destructor, so every truncated PNG leaked its error text (and the user got libpng's
// wording). OpenEXR allocates an attribute's declared size (up to 2 GiB) and the data window's offset
// table before reading either.
#include <string>

namespace prt::image {

/// Checks the file at `path` by its magic bytes; returns "" when it passes or is none of these
/// formats (nor readable: the reader reports that), else one line without the path:
/// - PNG (ISO/IEC 15948:2004, sections 5.2-5.3: the 8-byte signature, then chunks of a 4-byte
///   big-endian data length, a 4-byte type, the data and a 4-byte CRC): every chunk lies inside the
///   file, up to and including an IEND chunk (bytes after IEND are ignored, as libpng ignores them),
///   e.g. `truncated PNG: chunk "IDAT" at byte 57 declares 8192 data bytes but the file ends at byte 120`.
///   CRCs, chunk order and contents are left to libpng.
/// - OpenEXR ("OpenEXR File Layout", openexr.com: magic 20000630 and a version field, then one
///   header, or for multi-part files (version flag 0x1000) headers ended by an empty one; a header is
///   attributes ended by a zero byte, an attribute a zero-terminated name and type name of at most
///   255 bytes each, a little-endian int32 size and that many value bytes): every attribute lies
///   inside the file, fixed-size types (box2i, float, v2f, ...) declare exactly their size, chlist,
///   preview and stringvector values exactly fill theirs, and every "dataWindow" (box2i) is within
///   prt's limits. Chunks are left to OpenEXR.
/// - BMP (file-header magic BM, BA, CI, CP or PT; a Windows DIB header of 40, 52, 56, 108 or 124
///   bytes with int32 width and height, or the 12-byte OS/2 one with uint16): the width and the
///   height's magnitude within prt's limits (OpenImageIO 2.4 multiplies them in int for an RLE
///   buffer: large sides overflow and abort).
/// Reads only headers.
std::string structure_problem(const std::string& path);

}  // namespace prt::image
