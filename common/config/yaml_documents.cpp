// readYamlDocuments (yaml_documents.hpp): one pass over the documents with an event handler that
// only notes each root's kind and place, stopping where the parser repeats itself, then the first
// document as a node by YAML::Load, which parses one document and so cannot loop.
#include "common/config/yaml_documents.hpp"

#include <yaml-cpp/eventhandler.h>

#include <optional>
#include <sstream>

namespace wsn::common::config {
namespace {

/// Notes a document's root: whether it is null, and where it starts.
class RootNoter : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { root(mark, true); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { root(mark, false); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    root(mark, false);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(mark);
  }
  void OnSequenceEnd() override { --depth_; }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(mark);
  }
  void OnMapEnd() override { --depth_; }

  bool null() const { return null_; }
  const std::optional<YAML::Mark>& mark() const { return mark_; }

 private:
  void root(const YAML::Mark& mark, bool null) {
    if (depth_ > 0 || mark_) return;
    mark_ = mark;
    null_ = null;
  }
  void open(const YAML::Mark& mark) {
    root(mark, false);
    ++depth_;
  }
  int depth_ = 0;
  bool null_ = true;
  std::optional<YAML::Mark> mark_;
};

bool samePlace(const YAML::Mark& a, const YAML::Mark& b) { return a.pos == b.pos && a.line == b.line && a.column == b.column; }

}  // namespace

YamlDocuments readYamlDocuments(const std::string& text) {
  YamlDocuments documents;
  std::istringstream in(text);
  YAML::Parser parser(in);
  std::optional<YAML::Mark> last_null;
  while (true) {
    RootNoter noter;
    if (!parser.HandleNextDocument(noter)) break;
    if (noter.null()) {
      // yaml-cpp 0.7 hands out an empty document at the same place for ever when it cannot go on.
      if (noter.mark() && last_null && samePlace(*noter.mark(), *last_null))
        throw YAML::ParserException(*noter.mark(), "the YAML parser cannot go past this point");
      if (noter.mark()) last_null = noter.mark();
    } else if (documents.count > 0 && documents.later_content_line == 0) {
      documents.later_content_line = noter.mark() ? noter.mark()->line + 1 : 1;
    }
    ++documents.count;
  }
  documents.first = YAML::Load(text);
  return documents;
}

}  // namespace wsn::common::config
