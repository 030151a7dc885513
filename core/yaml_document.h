// Parsing one YAML document strictly: the checks yaml-cpp does not make (a key given twice in
// one mapping, a second document, a number with a leading zero). Header-only, so that every
// target that reads YAML through core/yaml_file.h or core/config_io.h (the fuzz targets too)
// has it without another source file.
#pragma once

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"

namespace uwbsar {
namespace yaml_document {

/// Walks the event stream of one document (aliases are not expanded, so the walk is linear in
/// the text) and throws at the first key that a mapping already holds.
class DuplicateKeyCheck : public YAML::EventHandler {
 public:
  explicit DuplicateKeyCheck(const std::string& source) : source_(source) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { OnLeaf(mark, "~", true); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { OnLeaf(mark, "", false); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    OnLeaf(mark, value, true);
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    Push(false);
  }
  void OnSequenceEnd() override { frames_.pop_back(); }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    Push(true);
  }
  void OnMapEnd() override { frames_.pop_back(); }

 private:
  struct Frame {
    bool is_map = false;
    bool expect_key = true;            ///< a mapping: the next node is a key
    std::string path;                  ///< dotted path of this container ("" at the top)
    std::string key;                   ///< a mapping: the key whose value comes next
    std::size_t index = 0;             ///< a sequence: the next item's index
    std::map<std::string, int> lines;  ///< a mapping: its plain keys and their lines (1-based)
  };

  /// The path of the node that comes next in the innermost container, and its role there.
  std::string NextPath(bool* is_key) {
    *is_key = false;
    if (frames_.empty()) return "";
    Frame& f = frames_.back();
    if (!f.is_map) return f.path + "[" + std::to_string(f.index++) + "]";
    if (f.expect_key) {
      *is_key = true;
      f.expect_key = false;
      return f.path;
    }
    f.expect_key = true;
    return f.path.empty() ? f.key : f.path + "." + f.key;
  }

  void Push(bool is_map) {
    bool is_key = false;
    std::string path = NextPath(&is_key);
    if (is_key) {
      frames_.back().key = "<complex key>";
      path = frames_.back().path;
    }
    Frame frame;
    frame.is_map = is_map;
    frame.path = std::move(path);
    frames_.push_back(std::move(frame));
  }

  void OnLeaf(const YAML::Mark& mark, const std::string& value, bool plain_key) {
    bool is_key = false;
    NextPath(&is_key);
    if (!is_key) return;
    Frame& f = frames_.back();
    f.key = plain_key ? value : "<alias>";
    if (!plain_key) return;
    const int line = mark.line + 1;
    const auto [it, inserted] = f.lines.emplace(value, line);
    if (inserted) return;
    const std::string dotted = f.path.empty() ? value : f.path + "." + value;
    throw InputError(source_ + ":" + std::to_string(line) + ": duplicate key '" + dotted +
                     "' (first at line " + std::to_string(it->second) + ")");
  }

  const std::string& source_;
  std::vector<Frame> frames_;
};

/// Only notes where the next document starts.
class DocumentStart : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override {
    if (line < 0) line = mark.line + 1;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
  int line = -1;
};

}  // namespace yaml_document

/// The one document of `text`. Throws InputError naming `source` and the line on a syntax
/// error, on a key that its mapping already holds ("duplicate key 'a.b' (first at line N)",
/// the dotted path as the configuration names keys, list items as [i]) and on a second
/// document. An empty text (or only comments) gives a null node.
inline YAML::Node ParseYamlDocument(const std::string& text, const std::string& source) {
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    yaml_document::DuplicateKeyCheck duplicates(source);
    if (!parser.HandleNextDocument(duplicates)) return YAML::Node();
    yaml_document::DocumentStart second;
    if (parser.HandleNextDocument(second)) {
      throw InputError(source + (second.line > 0 ? ":" + std::to_string(second.line) : "") +
                       ": a second YAML document (after '---'); a file holds one document");
    }
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(source + (e.mark.line >= 0 ? ":" + std::to_string(e.mark.line + 1) : "") +
                     ": YAML syntax error: " + e.msg);
  }
}

/// True for a number written with a leading zero ("010", "-007", "00.5"): YAML 1.1 reads it as
/// octal, YAML 1.2 as decimal, so its value is ambiguous and it is refused.
inline bool HasLeadingZero(const std::string& scalar) {
  std::size_t i = 0;
  if (i < scalar.size() && (scalar[i] == '-' || scalar[i] == '+')) ++i;
  return i + 1 < scalar.size() && scalar[i] == '0' && scalar[i + 1] >= '0' && scalar[i + 1] <= '9';
}

}  // namespace uwbsar
