#include "renderer/xml_reader.h"

#include <cstdint>

#include "renderer/json_fields.h"

namespace glint {

const std::string* XmlElement::attribute(const std::string& key) const {
  for (const auto& [k, v] : attributes)
    if (k == key) return &v;
  return nullptr;
}

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_name_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == ':' ||
         static_cast<unsigned char>(c) >= 0x80;
}
bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.'; }

void append_utf8(std::string& out, uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

class XmlParser {
 public:
  XmlParser(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  XmlElement document() {
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
    if (!json_fields::is_valid_utf8(text_)) fail("the file is not UTF-8 text");
    if (text_.find('\0') != std::string::npos) fail("the file holds a NUL byte");
    skip_space();
    if (starts("<?xml")) {
      const size_t end = text_.find("?>", pos_);
      if (end == std::string::npos) fail("the XML declaration is not closed by ?>");
      advance_to(end + 2);
    }
    skip_misc();
    if (pos_ >= text_.size() || text_[pos_] != '<') fail("expected the root element");
    XmlElement root = element(1);
    skip_misc();
    if (pos_ < text_.size()) fail("content after the root element <" + root.name + ">");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw ProjectError(file_, "line " + std::to_string(line_), problem);
  }
  bool starts(const char* s) const { return text_.compare(pos_, std::char_traits<char>::length(s), s) == 0; }
  void advance_to(size_t to) {
    for (; pos_ < to && pos_ < text_.size(); ++pos_)
      if (text_[pos_] == '\n') ++line_;
  }
  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) advance_to(pos_ + 1);
  }
  // Whitespace and comments; anything else outside a tag is refused by the caller.
  void skip_misc() {
    for (;;) {
      skip_space();
      if (starts("<!--")) {
        const size_t end = text_.find("-->", pos_ + 4);
        if (end == std::string::npos) fail("a comment is not closed by -->");
        advance_to(end + 3);
      } else if (starts("<!DOCTYPE") || starts("<!ENTITY")) {
        fail("document type declarations are not supported");
      } else if (starts("<![CDATA[")) {
        fail("CDATA sections are not supported");
      } else if (starts("<?")) {
        fail("processing instructions are not supported");
      } else {
        return;
      }
    }
  }

  std::string name() {
    const size_t start = pos_;
    if (pos_ >= text_.size() || !is_name_start(text_[pos_])) fail("expected a name");
    while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  std::string entity() {  // at '&'
    const size_t end = text_.find(';', pos_);
    if (end == std::string::npos || end - pos_ > 12) fail("'&' does not start an entity such as &amp;");
    const std::string ref = text_.substr(pos_ + 1, end - pos_ - 1);
    pos_ = end + 1;
    if (ref == "lt") return "<";
    if (ref == "gt") return ">";
    if (ref == "amp") return "&";
    if (ref == "quot") return "\"";
    if (ref == "apos") return "'";
    if (ref.size() > 1 && ref[0] == '#') {
      const bool hex = ref[1] == 'x';
      const std::string digits = ref.substr(hex ? 2 : 1);
      uint32_t code = 0;
      for (char c : digits) {
        const int d = c >= '0' && c <= '9' ? c - '0' : hex && c >= 'a' && c <= 'f' ? c - 'a' + 10
                    : hex && c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0 || code > 0x10FFFF) fail("bad character reference &" + ref + ";");
        code = code * (hex ? 16 : 10) + d;
      }
      if (digits.empty() || code == 0 || code > 0x10FFFF || (code >= 0xD800 && code < 0xE000))
        fail("bad character reference &" + ref + ";");
      std::string out;
      append_utf8(out, code);
      return out;
    }
    fail("unknown entity &" + json_fields::clip(ref, 12) + ";");
  }

  std::string attribute_value() {
    if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) fail("expected a quoted attribute value");
    const char quote = text_[pos_++];
    std::string value;
    for (;;) {
      if (pos_ >= text_.size()) fail("an attribute value is not closed");
      const char c = text_[pos_];
      if (c == quote) break;
      if (c == '<') fail("'<' inside an attribute value");
      if (c == '&') {
        value += entity();
      } else {
        if (c == '\n') ++line_;
        value += c;
        ++pos_;
      }
    }
    ++pos_;
    return value;
  }

  XmlElement element(int depth) {  // at '<'
    if (depth > kMaxXmlDepth) fail("elements nest more than " + std::to_string(kMaxXmlDepth) + " levels deep");
    XmlElement e;
    e.line = line_;
    ++pos_;
    e.name = name();
    for (;;) {
      const size_t before = pos_;
      skip_space();
      if (pos_ >= text_.size()) fail("<" + e.name + "> is not closed");
      if (starts("/>")) {
        pos_ += 2;
        return e;
      }
      if (text_[pos_] == '>') {
        ++pos_;
        break;
      }
      if (pos_ == before) fail("expected a space, '>' or '/>' in <" + e.name + ">");
      std::string key = name();
      skip_space();
      if (pos_ >= text_.size() || text_[pos_] != '=') fail("attribute " + key + " of <" + e.name + "> has no '='");
      ++pos_;
      skip_space();
      std::string value = attribute_value();
      if (e.attribute(key)) fail("<" + e.name + "> has attribute " + key + " twice");
      e.attributes.emplace_back(std::move(key), std::move(value));
    }
    for (;;) {
      skip_misc();
      if (pos_ >= text_.size()) fail("<" + e.name + "> (line " + std::to_string(e.line) + ") is not closed");
      if (text_[pos_] != '<') fail("text inside <" + e.name + "> (scene files keep values in attributes)");
      if (starts("</")) {
        pos_ += 2;
        const std::string closing = name();
        skip_space();
        if (pos_ >= text_.size() || text_[pos_] != '>') fail("expected '>' after </" + closing);
        ++pos_;
        if (closing != e.name)
          fail("<" + e.name + "> (line " + std::to_string(e.line) + ") is closed by </" + closing + ">");
        return e;
      }
      e.children.push_back(element(depth + 1));
    }
  }

  const std::string& text_;
  const std::string& file_;
  size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace

XmlElement parse_xml(const std::string& text, const std::string& file_label) {
  return XmlParser(text, file_label).document();
}

}  // namespace glint
