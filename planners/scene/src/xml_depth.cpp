// A bound on the element nesting of XML files, checked before a parser that
// recurses once per level (urdfdom's TinyXML, assimp's COLLADA reader) sees
// them: a file nested tens of thousands deep would overflow its stack.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <string>

#include "scene_detail.h"

namespace mddual::scene::detail {
namespace {

/// Walks `text` from a position, counting lines.
class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}

  bool done() const { return pos_ >= text_.size(); }
  char peek() const { return text_[pos_]; }
  int line() const { return line_; }
  bool startsWith(std::string_view prefix) const { return text_.substr(pos_, prefix.size()) == prefix; }

  /// Moves past the next occurrence of `end` (to the end of the text if none).
  void skipPast(std::string_view end) {
    const std::size_t found = text_.find(end, pos_);
    moveTo(found == std::string_view::npos ? text_.size() : found + end.size());
  }

  /// Moves past the '>' that closes the current markup, ignoring '>' inside
  /// quoted values and, when `brackets`, inside [...] (a DOCTYPE's internal
  /// subset). Returns the character before that '>' (0 if none).
  char skipTag(bool brackets) {
    char quote = 0;
    int square = 0;
    char previous = 0;
    while (!done()) {
      const char c = peek();
      advance();
      if (quote != 0) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (brackets && c == '[') {
        ++square;
      } else if (brackets && c == ']') {
        square = std::max(0, square - 1);
      } else if (c == '>' && square == 0) {
        return previous;
      }
      if (std::isspace(static_cast<unsigned char>(c)) == 0) previous = c;
    }
    return 0;
  }

  void advance() {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }

 private:
  void moveTo(std::size_t end) {
    line_ += static_cast<int>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                         text_.begin() + static_cast<std::ptrdiff_t>(end), '\n'));
    pos_ = end;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace

XmlDepth xmlElementDepth(std::string_view text, int limit) {
  XmlDepth deepest;
  int depth = 0;
  Cursor at(text);
  while (!at.done()) {
    if (at.peek() != '<') {
      at.advance();
      continue;
    }
    if (at.startsWith("<!--")) {
      at.skipPast("-->");
    } else if (at.startsWith("<![CDATA[")) {
      at.skipPast("]]>");
    } else if (at.startsWith("<?")) {
      at.skipPast("?>");
    } else if (at.startsWith("<!")) {
      at.skipTag(/*brackets=*/true);  // <!DOCTYPE ... [ <!ENTITY ...> ... ]>
    } else if (at.startsWith("</")) {
      at.skipTag(/*brackets=*/false);
      depth = std::max(0, depth - 1);
    } else {
      const int line = at.line();
      const bool self_closing = at.skipTag(/*brackets=*/false) == '/';
      if (self_closing) continue;
      ++depth;
      if (depth > deepest.depth) {
        deepest.depth = depth;
        deepest.line = line;
        if (depth > limit) break;
      }
    }
  }
  return deepest;
}

std::string requireShallowXml(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw SceneError(display(file) + ": cannot read the file");
  std::string xml = text.str();
  const XmlDepth found = xmlElementDepth(xml, kMaxXmlElementDepth);
  if (found.depth > kMaxXmlElementDepth) {
    throw SceneError(display(file) + ":" + std::to_string(found.line) + ": XML elements nested more than " +
                     std::to_string(kMaxXmlElementDepth) + " deep (the most this loader reads: its XML parser " +
                     "recurses once per level; real files nest about ten deep)");
  }
  return xml;
}

bool isXmlMesh(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".dae";
}

}  // namespace mddual::scene::detail
