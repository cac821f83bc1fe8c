// A structural check of an OpenEXR file's headers, made before OpenImageIO sees the bytes.
// OpenEXR sizes an attribute's buffer from the size the header declares and only then reads it,
// so a few hundred bytes declaring a 1.4 GB string made it allocate that much and read for
// minutes, inside its own header read, before snee learns any image size to check against the
// memory budget. Here every attribute of every header (single-part, tiled, deep and multi-part
// files alike) is walked without allocating: its name and type must end within OpenEXR's name
// limit, its declared size must fit in the bytes left in the file, and a value of a type
// OpenEXR reads by its own layout (fixed-size types, channel lists, previews, string vectors)
// must take exactly the declared size, since OpenEXR carries on from where its layout ended.
// The file itself is within the memory budget (input_file.h), so no header-sized allocation
// can exceed it either. What the values mean is left to OpenEXR.
#pragma once

#include <string>
#include <string_view>

namespace snee {

// Whether `bytes` start with the OpenEXR magic number (76 2f 31 01).
bool has_exr_magic(std::string_view bytes);

// For bytes that start with the EXR magic, throws SceneError "<path>: EXR header ..." naming the
// attribute (and header, in a multi-part file) and the sizes when the version field is not one
// OpenEXR 2 defines, a name or type is too long or unterminated, a declared size is negative,
// larger than the bytes that follow it or not what the value of its type takes, or the file
// ends inside the headers. Any other bytes are
// left alone.
void check_exr_header(std::string_view bytes, const std::string& path);

}  // namespace snee
