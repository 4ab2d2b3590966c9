// A strict reader for the XML that scene files of other renderers use (Mitsuba 3): elements with
// attributes, comments, an XML declaration, the five predefined entities and character
// references. Anything else (a DOCTYPE, CDATA, processing instructions past the declaration,
// text between elements) is an error naming the line, so a file is never half understood.
// Written here rather than taken from a library: the subset is small, its errors carry the line
// of each element for the scene readers' messages, and it has no dependency to package.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "renderer/project_error.h"

namespace glint {

struct XmlElement {
  std::string name;
  int line = 0;  // where its start tag begins, from 1
  std::vector<std::pair<std::string, std::string>> attributes;  // in the file's order
  std::vector<XmlElement> children;

  // The attribute's value, or nullptr when the element has none of that name.
  const std::string* attribute(const std::string& key) const;
};

// Elements nested deeper than this are refused (a scene needs about 6 levels).
constexpr int kMaxXmlDepth = 64;

// The document's root element. Throws ProjectError(file_label, "line N", problem) at the first
// problem, e.g. "scene.xml: line 12: <bsdf> is closed by </shape>".
XmlElement parse_xml(const std::string& text, const std::string& file_label);

}  // namespace glint
