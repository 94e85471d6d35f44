#include "cli_common/cli_errors.hpp"

#include <algorithm>
#include <regex>
#include <sstream>
#include <vector>

namespace visgrab::cli {

namespace {

// The names of `app`'s commands, comma-separated.
std::string commandNames(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return names;
}

// "--out DIR" or "FILE": an option as the help shows it.
std::string optionWithType(const CLI::Option& opt) {
  if (opt.get_positional()) return opt.get_name();
  const std::string type = opt.get_type_name();
  return opt.get_name() + (type.empty() || opt.get_expected_max() == 0 ? "" : " " + type);
}

constexpr std::size_t kHelpWidth = 100;
constexpr std::size_t kFirstColumn = 36;

// `text` broken into lines of at most `width` characters at spaces (CLI11 indents each line
// after a '\n' to the description column).
std::string wrap(const std::string& text, std::size_t width) {
  std::string out;
  std::size_t lineLength = 0;
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    if (lineLength > 0 && lineLength + 1 + word.size() > width) {
      out += "\n";
      lineLength = 0;
    } else if (lineLength > 0) {
      out += " ";
      ++lineLength;
    }
    out += word;
    lineLength += word.size();
  }
  return out;
}

// CLI11's layout with long descriptions wrapped to kHelpWidth columns.
class WrappingFormatter : public CLI::Formatter {
 public:
  std::string make_option_desc(const CLI::Option* opt) const override {
    return wrap(opt->get_description(), kHelpWidth - kFirstColumn);
  }
  std::string make_subcommand(const CLI::App* sub) const override {
    // The first sentence in the list of commands; all of it in the command's own help.
    std::string summary = sub->get_description();
    if (const auto stop = summary.find(". "); stop != std::string::npos) {
      summary = summary.substr(0, stop + 1);
    }
    std::ostringstream out;
    CLI::detail::format_help(out, sub->get_display_name(true),
                             wrap(summary, kHelpWidth - kFirstColumn), kFirstColumn);
    return out.str();
  }
  std::string make_description(const CLI::App* app) const override {
    const std::string text = app->get_description();
    return text.empty() ? std::string() : wrap(text, kHelpWidth) + "\n";
  }
};

}  // namespace

std::shared_ptr<CLI::Formatter> makeHelpFormatter() {
  auto f = std::make_shared<WrappingFormatter>();
  f->label("Usage", "usage");
  f->label("SUBCOMMAND", "COMMAND");
  f->label("SUBCOMMANDS", "COMMANDS");
  f->label("Subcommands", "Commands");
  f->label("REQUIRED", "(required)");
  f->column_width(kFirstColumn);
  return f;
}

std::string describeParseError(const CLI::ParseError& e, const CLI::App& cmd) {
  const std::string what = e.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
    // "The following argument(s) was/were not expected: A B", in command-line order.
    std::vector<std::string> extras;
    std::istringstream words(what.substr(what.find(": ") + 2));
    for (std::string w; words >> w;) extras.push_back(w);
    const auto option = std::find_if(extras.begin(), extras.end(),
                                     [](const std::string& s) { return s.rfind('-', 0) == 0; });
    if (option != extras.end()) return "unknown option " + *option;
    if (!extras.empty()) {
      if (!cmd.get_subcommands({}).empty()) {
        return "unknown command '" + extras.front() + "'; choose one of " + commandNames(cmd);
      }
      return "unexpected argument '" + extras.front() + "'";
    }
  }
  if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
    if (cmd.get_require_subcommand_min() > 0 && cmd.get_subcommands().empty()) {
      return "a command is required: one of " + commandNames(cmd);
    }
    for (const CLI::Option* opt : cmd.get_options()) {
      if (!opt->get_required() || opt->count() > 0) continue;
      if (opt->get_positional())
        return "missing " + opt->get_name() + " (" + opt->get_description() + ")";
      return optionWithType(*opt) + " is required";
    }
  }
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) != nullptr) {
    std::smatch m;
    static const std::regex twice("^(\\S+): At Most 1 required but received (\\d+)$");
    static const std::regex missing("^(\\S+): \\d+ required (.*) missing$");
    if (std::regex_match(what, m, twice)) {
      return m[1].str() + " is given " + m[2].str() + " times (once at most)";
    }
    if (std::regex_match(what, m, missing))
      return m[1].str() + ": expected " + m[2].str() + " after it";
  }
  if (dynamic_cast<const CLI::ValidationError*>(&e) != nullptr) {
    // "--time: must be > 0, got -1" from the checks below: "--time must be > 0, got -1".
    std::smatch m;
    static const std::regex check("^(--\\S+): (.*)$");
    if (std::regex_match(what, m, check)) return m[1].str() + " " + m[2].str();
  }
  return what;
}

}  // namespace visgrab::cli
