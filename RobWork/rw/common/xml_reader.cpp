#include "rw/common/xml_reader.hpp"

#include <xercesc/framework/MemBufInputSource.hpp>
#include <xercesc/framework/XMLPScanToken.hpp>
#include <xercesc/sax/Locator.hpp>
#include <xercesc/sax/SAXParseException.hpp>
#include <xercesc/sax2/Attributes.hpp>
#include <xercesc/sax2/DefaultHandler.hpp>
#include <xercesc/sax2/SAX2XMLReader.hpp>
#include <xercesc/sax2/XMLReaderFactory.hpp>
#include <xercesc/util/OutOfMemoryException.hpp>
#include <xercesc/util/PlatformUtils.hpp>
#include <xercesc/util/SecurityManager.hpp>
#include <xercesc/util/XMLException.hpp>
#include <xercesc/util/XMLUni.hpp>
#include <xercesc/validators/common/Grammar.hpp>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "rw/common/content_model.hpp"
#include "rw/common/strings.hpp"

namespace rw::common {

namespace xc = XERCES_CPP_NAMESPACE;

namespace {

constexpr std::size_t kMaxElementsPerFile = 250'000;

// Xerces is initialised once per process, thread-safely, and never terminated: other threads
// may be parsing at any time.
void ensureXercesInitialized() {
  static const bool initialised = [] {
    try {
      xc::XMLPlatformUtils::Initialize();
      return true;
    } catch (const xc::XMLException&) {
      return false;
    }
  }();
  if (!initialised) throw std::runtime_error("the XML library (Xerces-C) cannot be initialised");
}

// UTF-16 from Xerces to UTF-8 (unpaired surrogates become U+FFFD).
std::string toUtf8(const XMLCh* text, std::size_t length) {
  std::string out;
  out.reserve(length);
  for (std::size_t i = 0; i < length; ++i) {
    char32_t c = text[i];
    if (c >= 0xD800 && c <= 0xDBFF && i + 1 < length && text[i + 1] >= 0xDC00 &&
        text[i + 1] <= 0xDFFF) {
      c = 0x10000 + ((c - 0xD800) << 10) + (static_cast<char32_t>(text[i + 1]) - 0xDC00);
      ++i;
    } else if (c >= 0xD800 && c <= 0xDFFF) {
      c = 0xFFFD;
    }
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

std::string toUtf8(const XMLCh* text) {
  return text == nullptr ? std::string() : toUtf8(text, xc::XMLString::stringLen(text));
}

int clampToInt(XMLFileLoc value) {
  return static_cast<int>(std::min<XMLFileLoc>(value, std::numeric_limits<int>::max()));
}

// The text as handed to Xerces (wrapped in kFragmentElement right after the XML declaration)
// and the mapping from Xerces positions back to positions in the file as written.
class WrappedText {
 public:
  explicit WrappedText(std::string_view original) {
    std::size_t insert = 0;
    if (original.substr(0, 3) == "\xEF\xBB\xBF") insert = 3;
    if (original.substr(insert, 5) == "<?xml" && original.size() > insert + 5 &&
        (original[insert + 5] == ' ' || original[insert + 5] == '\t' ||
         original[insert + 5] == '\r' || original[insert + 5] == '\n')) {
      const auto end = original.find("?>", insert);
      if (end != std::string_view::npos) insert = end + 2;
    }
    const std::string open = "<" + std::string(kFragmentElement) + ">";
    text_.reserve(original.size() + 2 * open.size() + 1);
    text_.append(original.substr(0, insert));
    text_.append(open);
    text_.append(original.substr(insert));
    // Problems found at the closing wrapper (end of input) are reported after the last
    // non-blank character of the file.
    endOfContent_ = text_.find_last_not_of(" \t\r\n") + 1;
    if (endOfContent_ <= insert + open.size()) endOfContent_ = text_.size();
    text_.append("</" + std::string(kFragmentElement) + ">");
    buildLineTable();
    const auto [line, column] = lineColumnOf(insert);
    insertLine_ = line;
    insertColumn_ = column;
    wrapperLength_ = static_cast<int>(open.size());
  }

  const std::string& text() const { return text_; }

  // True if the markup at or just before Xerces position (line, column) starts with `prefix`.
  bool markupStartsWith(int line, int column, std::string_view prefix) const {
    const std::size_t offset = offsetOf(line, column);
    const std::size_t lt = text_.rfind('<', offset);
    return lt != std::string::npos && offset - lt <= prefix.size() &&
           std::string_view(text_).substr(lt, prefix.size()) == prefix;
  }

  // Position in the file as written for a Xerces position in the wrapped text.
  std::pair<int, int> unwrap(int line, int column) const {
    if (offsetOf(line, column) > endOfContent_)
      std::tie(line, column) = lineColumnOf(endOfContent_);
    if (line == insertLine_ && column > insertColumn_) {
      column = std::max(insertColumn_, column - wrapperLength_);
    }
    return {line, std::max(column, 1)};
  }

  // The character data that ends at Xerces position (line, column): back to the previous '>'.
  std::string textBefore(int line, int column) const {
    const std::size_t offset = offsetOf(line, column);
    const std::size_t gt = text_.rfind('>', offset == 0 ? 0 : offset - 1);
    if (gt == std::string::npos || gt >= offset) return {};
    return text_.substr(gt + 1, std::min<std::size_t>(offset - gt - 1, 200));
  }

  // Position of the '<' of the start tag that ends just before Xerces position (line, column).
  std::pair<int, int> startTagBefore(int line, int column) const {
    std::size_t offset = offsetOf(line, column);
    const std::size_t lt = text_.rfind('<', offset == 0 ? 0 : offset - 1);
    if (lt == std::string::npos) return unwrap(line, column);
    const auto [l, c] = lineColumnOf(lt);
    return unwrap(l, c);
  }

 private:
  void buildLineTable() {
    lineStart_.push_back(0);
    asciiLine_.push_back(true);
    for (std::size_t i = 0; i < text_.size(); ++i) {
      if (static_cast<unsigned char>(text_[i]) >= 0x80) asciiLine_.back() = false;
      if (text_[i] == '\n') {
        lineStart_.push_back(i + 1);
        asciiLine_.push_back(true);
      }
    }
  }

  // Xerces counts columns in characters; walk non-ASCII lines (short ones only) to find bytes.
  std::size_t offsetOf(int line, int column) const {
    if (line < 1) return 0;
    const auto index = std::min(static_cast<std::size_t>(line - 1), lineStart_.size() - 1);
    const std::size_t start = lineStart_[index];
    const std::size_t end = index + 1 < lineStart_.size() ? lineStart_[index + 1] : text_.size();
    const auto chars = static_cast<std::size_t>(std::max(column - 1, 0));
    if (asciiLine_[index] || end - start > kLongLine) return std::min(start + chars, end);
    std::size_t offset = start;
    for (std::size_t n = 0; n < chars && offset < end; ++n) {
      ++offset;
      while (offset < end && (static_cast<unsigned char>(text_[offset]) & 0xC0) == 0x80) ++offset;
    }
    return offset;
  }

  std::pair<int, int> lineColumnOf(std::size_t offset) const {
    const auto it = std::upper_bound(lineStart_.begin(), lineStart_.end(), offset);
    const auto index = static_cast<std::size_t>(it - lineStart_.begin()) - 1;
    const std::size_t start = lineStart_[index];
    std::size_t column = offset - start;
    if (!asciiLine_[index] && offset - start <= kLongLine) {
      column = 0;
      for (std::size_t i = start; i < offset; ++i) {
        if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) ++column;
      }
    }
    return {static_cast<int>(std::min<std::size_t>(index + 1, std::numeric_limits<int>::max())),
            static_cast<int>(std::min<std::size_t>(column + 1, std::numeric_limits<int>::max()))};
  }

  static constexpr std::size_t kLongLine = 1 << 16;

  std::string text_;
  std::vector<std::size_t> lineStart_;
  std::vector<bool> asciiLine_;
  int insertLine_ = 1;
  int insertColumn_ = 1;
  int wrapperLength_ = 0;
  std::size_t endOfContent_ = 0;
};

// Text between the first pair of single quotes after `after` in a Xerces message.
std::string quotedAfter(const std::string& message, std::string_view after) {
  const auto at = message.find(after);
  if (at == std::string::npos) return {};
  const auto open = message.find('\'', at + after.size());
  if (open == std::string::npos) return {};
  const auto close = message.find('\'', open + 1);
  if (close == std::string::npos) return {};
  return message.substr(open + 1, close - open - 1);
}

std::string shortened(std::string_view text) {
  text = trimXmlSpace(text);
  if (text.size() <= 40) return std::string(text);
  return std::string(text.substr(0, 37)) + "...";
}

// "(A|B|C)" -> "A, B, C"
std::string contentModelList(const std::string& model) {
  std::string out;
  for (char c : model) {
    if (c == '(' || c == ')' || c == '*' || c == '?' || c == '+') continue;
    if (c == '|' || c == ',') {
      out += ", ";
    } else {
      out += c;
    }
  }
  return out;
}

// The names of the elements a schema declares (`<xs:element name="...">`), for "did you mean".
std::vector<std::string> declaredElements(std::string_view schema) {
  std::vector<std::string> names;
  constexpr std::string_view kOpen = "<xs:element";
  for (std::size_t at = schema.find(kOpen); at != std::string_view::npos;
       at = schema.find(kOpen, at + kOpen.size())) {
    const std::size_t end = schema.find('>', at);
    const std::size_t name = schema.find("name=\"", at);
    if (name == std::string_view::npos || name > end) continue;
    const std::size_t close = schema.find('"', name + 6);
    if (close == std::string_view::npos) break;
    std::string n(schema.substr(name + 6, close - name - 6));
    if (n != kFragmentElement && std::find(names.begin(), names.end(), n) == names.end()) {
      names.push_back(std::move(n));
    }
  }
  return names;
}

// "; did you mean <X>?" for the declared element closest to `name`, or "".
std::string suggestElement(const std::string& name, const std::vector<std::string>& declared) {
  const std::string_view best = closestMatch(name, declared);
  return best.empty() ? std::string() : "; did you mean <" + std::string(best) + ">?";
}

// Why the children of `open` do not fit the content model `model` (Xerces's text), at the child
// concerned; empty if the model cannot be read or no reading of it agrees with Xerces.
// `rejected` is the child Xerces names as not allowed ("" when it reports missing elements).
// Xerces prints a group's own minOccurs/maxOccurs nowhere in that text: a device body, an
// unbounded choice, reads "(Frame|Joint|...)", as if it allowed one child. So the model as
// printed is taken when its verdict is Xerces's (the same child rejected, or none), else the
// model repeated, "(model)*"; an explanation of another child than the one Xerces rejected
// would send the author to the wrong line.
std::string explainChildren(const XmlElement& open, const std::string& model,
                            const std::string& rejected, SourceLocation& where) {
  std::vector<std::string> names;
  names.reserve(open.children.size());
  for (const XmlElement& c : open.children) names.push_back(c.name);
  for (const std::string& reading : {model, "(" + model + ")*"}) {
    const auto parsed = ContentModel::parse(reading);
    if (!parsed) return {};
    std::size_t index = 0;
    std::string message = parsed->explain(names, open.describe(), &index);
    if (message.empty()) continue;
    const bool agrees =
        rejected.empty() ? index == names.size() : index < names.size() && names[index] == rejected;
    if (!agrees) continue;
    where = index < open.children.size() ? open.children[index].location : open.location;
    if (message.find(" is given twice") != std::string::npos) {
      for (std::size_t j = 0; j < index; ++j) {
        if (open.children[j].name == names[index]) {
          message +=
              " (the first is at line " + std::to_string(open.children[j].location.line) + ")";
          break;
        }
      }
    }
    return message;
  }
  return {};
}

// Receives the SAX events of one parse and builds the element tree.
class TreeBuilder : public xc::DefaultHandler {
 public:
  TreeBuilder(const WrappedText& text, std::shared_ptr<const SourceFile> file, DiagnosticSink& sink,
              const XmlReaderOptions& options)
      : text_(text), file_(std::move(file)), sink_(sink), options_(options) {}

  bool stopped() const { return stopped_; }
  bool failed() const { return failed_; }
  std::vector<XmlElement> takeTopLevel() {
    if (stack_.empty()) return {};
    return std::move(stack_.front().children);
  }

  // Reports a validation error still waiting for its element (at the end of a parse).
  void flushPending() {
    if (pending_) reportPending(nullptr);
  }

  void setDocumentLocator(const xc::Locator* locator) override { locator_ = locator; }

  void startElement(const XMLCh*, const XMLCh*, const XMLCh* qname,
                    const xc::Attributes& attributes) override {
    if (stopped_) return;
    XmlElement element;
    element.name = toUtf8(qname);
    for (XMLSize_t i = 0; i < attributes.getLength(); ++i) {
      std::string name = toUtf8(attributes.getQName(i));
      if (name == "xmlns" || name.rfind("xmlns:", 0) == 0 || name.rfind("xsi:", 0) == 0) continue;
      element.attributes.push_back({std::move(name), toUtf8(attributes.getValue(i))});
    }
    const auto [line, column] = text_.startTagBefore(currentLine(), currentColumn());
    element.location = SourceLocation{file_, line, column};
    if (pending_ && (pending_->line != currentLine() || pending_->column != currentColumn())) {
      reportPending(nullptr);
      return;
    }
    stack_.push_back(std::move(element));
    if (pending_) {
      reportPending(&stack_.back());
      return;
    }
    if (static_cast<int>(stack_.size()) > kMaxElementDepth + 1) {
      fail(stack_.back().location,
           "elements are nested deeper than " + std::to_string(kMaxElementDepth) + " levels");
    } else if (++elementCount_ > kMaxElementsPerFile) {
      fail(stack_.back().location,
           "the file has more than " + std::to_string(kMaxElementsPerFile) + " elements");
    }
  }

  void endElement(const XMLCh*, const XMLCh*, const XMLCh*) override {
    if (stopped_) return;
    if (pending_) reportPending(nullptr);
    if (stack_.size() <= 1) return;
    XmlElement done = std::move(stack_.back());
    stack_.pop_back();
    stack_.back().children.push_back(std::move(done));
  }

  void characters(const XMLCh* chars, const XMLSize_t length) override {
    if (stopped_ || stack_.empty()) return;
    stack_.back().text += toUtf8(chars, length);
  }

  void error(const xc::SAXParseException& e) override {
    if (stopped_ || pending_) return;
    pending_ = Pending{toUtf8(e.getMessage()), clampToInt(e.getLineNumber()),
                       clampToInt(e.getColumnNumber())};
  }

  void fatalError(const xc::SAXParseException& e) override {
    if (stopped_) return;
    // A document that is not well-formed has no structure to validate: a validation error still
    // pending (an unclosed <Hand ...> seen as an element with text in it, say) is a consequence,
    // and the well-formedness error is the one to fix.
    pending_.reset();
    std::string message = toUtf8(e.getMessage());
    const std::string wrapperEnd = "end of tag '" + std::string(kFragmentElement) + "'";
    if (message.find(wrapperEnd) != std::string::npos) {
      message = "closing tag without a matching start tag";
    } else if (text_.markupStartsWith(clampToInt(e.getLineNumber()),
                                      clampToInt(e.getColumnNumber()), "<!DOCTYPE")) {
      message = "DOCTYPE declarations are not supported (RobWork's formats have none)";
    } else if (message.find("expected end of tag") != std::string::npos && stack_.size() > 1) {
      const SourceLocation& open = stack_.back().location;
      message += " (opened at line " + std::to_string(open.line) + ")";
    }
    const auto [line, column] =
        text_.unwrap(clampToInt(e.getLineNumber()), clampToInt(e.getColumnNumber()));
    fail(SourceLocation{file_, line, column}, "not well-formed XML: " + message);
  }

  void warning(const xc::SAXParseException&) override {}

 private:
  struct Pending {
    std::string message;
    int line;
    int column;
  };

  int currentLine() const { return locator_ ? clampToInt(locator_->getLineNumber()) : 0; }
  int currentColumn() const { return locator_ ? clampToInt(locator_->getColumnNumber()) : 0; }

  void fail(const SourceLocation& where, std::string message) {
    sink_.error(where, std::move(message));
    stopped_ = true;
    failed_ = true;
  }

  // Reports the pending validation error; `started` is the element whose start tag it is about
  // (attributes, unknown element), otherwise it concerns the innermost open element.
  void reportPending(const XmlElement* started) {
    const Pending p = std::move(*pending_);
    pending_.reset();
    const XmlElement* open = nullptr;
    if (started != nullptr) {
      if (stack_.size() >= 2) open = &stack_[stack_.size() - 2];
    } else if (!stack_.empty()) {
      open = &stack_.back();
    }
    const auto [line, column] = text_.unwrap(p.line, p.column);
    SourceLocation where{file_, line, column};
    rejectedText_ = text_.textBefore(p.line, p.column);
    std::string message = explain(p.message, started, open, where);
    fail(where, std::move(message));
  }

  std::string explain(const std::string& xerces, const XmlElement* started, const XmlElement* open,
                      SourceLocation& where) const;

  std::string explainContentError(const std::string& xerces, const XmlElement& open,
                                  SourceLocation& where) const;

  const WrappedText& text_;
  std::shared_ptr<const SourceFile> file_;
  DiagnosticSink& sink_;
  const XmlReaderOptions& options_;
  const xc::Locator* locator_ = nullptr;
  std::vector<XmlElement> stack_;
  std::optional<Pending> pending_;
  std::string rejectedText_;
  std::size_t elementCount_ = 0;
  bool stopped_ = false;
  bool failed_ = false;
};

std::string TreeBuilder::explain(const std::string& xerces, const XmlElement* started,
                                 const XmlElement* open, SourceLocation& where) const {
  const bool openIsWrapper = open == nullptr || open->name == kFragmentElement;
  if (started != nullptr) {
    where = started->location;
    const std::string self = started->describe();
    if (xerces.find("no declaration found for element") != std::string::npos) {
      return "unknown element <" + started->name + ">" +
             (openIsWrapper ? std::string() : " in " + open->describe()) +
             suggestElement(started->name, declaredElements(options_.schema));
    }
    if (xerces.find("is not declared for element") != std::string::npos) {
      return self + ": unknown attribute \"" + quotedAfter(xerces, "attribute") + "\"";
    }
    if (xerces.find("missing required attribute") != std::string::npos) {
      return self + ": missing required attribute \"" +
             quotedAfter(xerces, "missing required attribute") + "\"";
    }
    if (options_.explainValueError) {
      const std::string precise = options_.explainValueError(*started);
      if (!precise.empty()) return self + ": " + precise;
    }
    return self + ": " + xerces;
  }
  if (open == nullptr) return xerces;
  return explainContentError(xerces, *open, where);
}

std::string TreeBuilder::explainContentError(const std::string& xerces, const XmlElement& open,
                                             SourceLocation& where) const {
  const bool isWrapper = open.name == kFragmentElement;
  const bool contentModelError =
      xerces.find("is not allowed for content model") != std::string::npos ||
      xerces.find("missing elements in content model") != std::string::npos;
  if (contentModelError && !isWrapper) {
    const bool notAllowed = xerces.find("is not allowed for content model") != std::string::npos;
    std::string message = explainChildren(open, quotedAfter(xerces, "content model"),
                                          notAllowed ? quotedAfter(xerces, "element") : "", where);
    if (!message.empty()) return message;
  }
  if (xerces.find("is not allowed for content model") != std::string::npos) {
    const std::string child = quotedAfter(xerces, "element");
    for (const XmlElement& c : open.children) {
      if (c.name == child) {
        where = c.location;
        break;
      }
    }
    if (isWrapper) return "<" + child + "> is not allowed here";
    return "<" + child + "> is not allowed in " + open.describe() +
           "; expected one of: " + contentModelList(quotedAfter(xerces, "content model"));
  }
  if (xerces.find("no character data is allowed") != std::string::npos) {
    // Xerces does not pass rejected text on; take it from the source.
    const std::string text = shortened(trimXmlSpace(open.text).empty() ? rejectedText_ : open.text);
    if (isWrapper) return "text outside of the elements (\"" + text + "\")";
    where = open.location;
    return open.describe() + ": text is not allowed here (\"" + text + "\")";
  }
  if (isWrapper) return xerces;
  where = open.location;
  if (xerces.find("which is not equal to length facet value") != std::string::npos) {
    return open.describe() + ": expected " + quotedAfter(xerces, "length facet value") +
           " numbers, got " + quotedAfter(xerces, "has length") + " (\"" + shortened(open.text) +
           "\")";
  }
  if (options_.explainValueError) {
    const std::string precise = options_.explainValueError(open);
    if (!precise.empty()) return open.describe() + ": " + precise;
  }
  return open.describe() + ": " + xerces;
}

}  // namespace

struct XmlReader::Impl {
  XmlReaderOptions options;
  xc::SecurityManager security;
  std::unique_ptr<xc::SAX2XMLReader> reader;
  bool grammarLoaded = false;

  // After a Xerces exception the reader's state is unknown: start afresh next time.
  void discardReader() {
    reader.reset();
    grammarLoaded = false;
  }

  void makeReader() {
    ensureXercesInitialized();
    reader.reset(xc::XMLReaderFactory::createXMLReader());
    const bool validate = !options.schema.empty();
    reader->setFeature(xc::XMLUni::fgSAX2CoreNameSpaces, true);
    reader->setFeature(xc::XMLUni::fgSAX2CoreNameSpacePrefixes, false);
    reader->setFeature(xc::XMLUni::fgSAX2CoreValidation, validate);
    reader->setFeature(xc::XMLUni::fgXercesDynamic, false);
    reader->setFeature(xc::XMLUni::fgXercesSchema, validate);
    reader->setFeature(xc::XMLUni::fgXercesSchemaFullChecking, false);
    reader->setFeature(xc::XMLUni::fgXercesLoadSchema, false);
    reader->setFeature(xc::XMLUni::fgXercesLoadExternalDTD, false);
    reader->setFeature(xc::XMLUni::fgXercesSkipDTDValidation, true);
    reader->setFeature(xc::XMLUni::fgXercesDisableDefaultEntityResolution, true);
    reader->setFeature(xc::XMLUni::fgXercesIdentityConstraintChecking, false);
    reader->setFeature(xc::XMLUni::fgXercesUseCachedGrammarInParse, validate);
    reader->setFeature(xc::XMLUni::fgXercesCacheGrammarFromParse, false);
    security.setEntityExpansionLimit(100);
    reader->setProperty(xc::XMLUni::fgXercesSecurityManager, &security);
  }

  void loadGrammar() {
    if (grammarLoaded || options.schema.empty()) return;
    xc::MemBufInputSource source(reinterpret_cast<const XMLByte*>(options.schema.data()),
                                 options.schema.size(), "visgrab-schema.xsd");
    if (reader->loadGrammar(source, xc::Grammar::SchemaGrammarType, true) == nullptr) {
      throw std::runtime_error("the built-in XML schema cannot be compiled");
    }
    grammarLoaded = true;
  }
};

XmlReader::XmlReader(XmlReaderOptions options) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
}

XmlReader::~XmlReader() = default;

std::optional<std::vector<XmlElement>> XmlReader::parse(
    std::string_view text, const std::shared_ptr<const SourceFile>& file, DiagnosticSink& sink) {
  const WrappedText wrapped(text);
  TreeBuilder builder(wrapped, file, sink, impl_->options);
  const SourceLocation whole{file, 0, 0};
  try {
    if (!impl_->reader) impl_->makeReader();
    impl_->loadGrammar();
    impl_->reader->setContentHandler(&builder);
    impl_->reader->setErrorHandler(&builder);
    xc::MemBufInputSource input(reinterpret_cast<const XMLByte*>(wrapped.text().data()),
                                wrapped.text().size(), "document");
    xc::XMLPScanToken token;
    if (impl_->reader->parseFirst(input, token)) {
      while (!builder.stopped() && impl_->reader->parseNext(token)) {
      }
    }
    impl_->reader->parseReset(token);
    builder.flushPending();
  } catch (const xc::OutOfMemoryException&) {
    sink.error(whole, "out of memory while reading XML");
    impl_->discardReader();
    return std::nullopt;
  } catch (const xc::XMLException& e) {
    if (!builder.failed()) sink.error(whole, "XML error: " + toUtf8(e.getMessage()));
    impl_->discardReader();
    return std::nullopt;
  } catch (const xc::SAXException& e) {
    if (!builder.failed()) sink.error(whole, "XML error: " + toUtf8(e.getMessage()));
    impl_->discardReader();
    return std::nullopt;
  }
  if (impl_->reader) {
    impl_->reader->setContentHandler(nullptr);
    impl_->reader->setErrorHandler(nullptr);
  }
  if (builder.failed()) return std::nullopt;
  return builder.takeTopLevel();
}

}  // namespace rw::common
