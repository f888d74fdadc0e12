#include "cli.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace facet::cli {

std::string Parsed::get(const std::string& name, const std::string& fallback) const {
    auto it = values.find(name);
    return it == values.end() ? fallback : it->second;
}

std::vector<std::string> Parsed::all(const std::string& name) const {
    auto it = lists.find(name);
    return it == lists.end() ? std::vector<std::string>{} : it->second;
}

Parser::Parser(std::string program, std::string usage, std::string description)
    : program_(std::move(program)), usage_(std::move(usage)), description_(std::move(description)) {
    flag("--help", "show this help and exit");
    flag("--version", "print the program version and exit");
}

Parser& Parser::option(std::string name, std::string value_name, std::string help) {
    options_.push_back({std::move(name), std::move(value_name), std::move(help)});
    return *this;
}

Parser& Parser::flag(std::string name, std::string help) { return option(std::move(name), "", std::move(help)); }

Parser& Parser::repeatable(std::string name, std::string value_name, std::string help) {
    options_.push_back({std::move(name), std::move(value_name), std::move(help), true});
    return *this;
}

Parsed Parser::parse(int argc, char** argv) const {
    Parsed parsed;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg.size() < 2 || arg.rfind("--", 0) != 0) {
            parsed.positional.push_back(arg);
            continue;
        }
        std::string value;
        bool inline_value = false;
        if (auto eq = arg.find('='); eq != std::string::npos) {
            value = arg.substr(eq + 1);
            arg = arg.substr(0, eq);
            inline_value = true;
        }
        const OptionSpec* spec = nullptr;
        for (const OptionSpec& o : options_)
            if (o.name == arg) spec = &o;
        if (!spec) throw std::invalid_argument("unknown option " + arg + " (see --help)");
        if (spec->value_name.empty()) {
            if (inline_value) throw std::invalid_argument("option " + arg + " takes no value");
        } else if (!inline_value) {
            if (i + 1 >= argc) throw std::invalid_argument("option " + arg + " needs a value " + spec->value_name);
            value = argv[++i];
        }
        if (spec->repeatable) parsed.lists[arg].push_back(value);
        else if (parsed.values.count(arg)) throw std::invalid_argument("option " + arg + " given twice");
        parsed.values[arg] = value;
    }
    return parsed;
}

std::string Parser::help_text() const {
    std::string text = "Usage: " + program_ + " " + usage_ + "\n\n" + description_ + "\n\nOptions:\n";
    for (const OptionSpec& o : options_) {
        std::string left = "  " + o.name + (o.value_name.empty() ? "" : " " + o.value_name);
        if (left.size() < 26) left.resize(26, ' ');
        else left += "\n" + std::string(26, ' ');
        text += left + o.help + "\n";
    }
    return text;
}

bool Parser::answered_help_or_version(const Parsed& parsed, const char* version) const {
    if (parsed.has("--help")) {
        std::fputs(help_text().c_str(), stdout);
        return true;
    }
    if (parsed.has("--version")) {
        std::printf("%s %s\n", program_.c_str(), version);
        return true;
    }
    return false;
}

int parse_int(const std::string& text, const std::string& what, int min, int max) {
    errno = 0;
    char* end = nullptr;
    long value = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE)
        throw std::invalid_argument(what + ": '" + text + "' is not an integer");
    if (value < min || value > max)
        throw std::invalid_argument(what + ": " + text + " is outside " + std::to_string(min) + ".." +
                                    std::to_string(max));
    return static_cast<int>(value);
}

double parse_double(const std::string& text, const std::string& what) {
    errno = 0;
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
        throw std::invalid_argument(what + ": '" + text + "' is not a finite number");
    return value;
}

BrdfModel brdf_option(const Parsed& args, BrdfModel fallback) {
    if (!args.has("--brdf")) return fallback;
    const auto brdf = parse_brdf_model(args.get("--brdf"));
    if (!brdf) throw std::invalid_argument("--brdf: expected gltf or thesis, got '" + args.get("--brdf") + "'");
    return *brdf;
}

}  // namespace facet::cli
