#pragma once
// The metadata map <-> typed EXR header attributes (metadata_keys.h says
// which key gets which type). Internal to output/: it includes OIIO.
#include <OpenImageIO/imageio.h>

#include <map>
#include <string>

namespace vesper {

// Adds every entry as an attribute, typed as metadata_type() says; throws
// ImageIoError naming `file` and the key when a typed value's text is not
// a number (or 16 numbers).
void put_metadata(OIIO::ImageSpec& spec, const std::map<std::string, std::string>& metadata,
                  const std::string& file);

// The `vesper:*` attributes as text: numbers as metadata_text.h writes them,
// so put_metadata then read_metadata gives back the same map.
std::map<std::string, std::string> read_metadata(const OIIO::ImageSpec& spec);

// One attribute as that text (int, float, double, M44f, string), or "".
std::string attribute_text(const OIIO::ParamValue& p);

}  // namespace vesper
