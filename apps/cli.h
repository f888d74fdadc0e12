#pragma once
// A small, strict command-line parser shared by the programs: unknown options, missing
// values and malformed numbers are errors that name the option.
#include <cstdio>
#include <map>
#include <stdexcept>
#include <optional>
#include <string>
#include <vector>

#include <facet/core/brdf_model.h>

namespace facet::cli {

struct OptionSpec {
    std::string name;         // "--out"
    std::string value_name;   // "DIR"; empty for a flag
    std::string help;
    bool repeatable = false;  // may be given several times (all values kept in order)
};

struct Parsed {
    std::map<std::string, std::string> values;  // option -> value ("" for flags)
    std::vector<std::string> positional;
    std::map<std::string, std::vector<std::string>> lists;  // repeatable options

    // Every value of a repeatable option, in the order given.
    std::vector<std::string> all(const std::string& name) const;

    bool has(const std::string& name) const { return values.count(name) != 0; }
    std::string get(const std::string& name, const std::string& fallback = "") const;
};

class Parser {
public:
    Parser(std::string program, std::string usage, std::string description);
    Parser& option(std::string name, std::string value_name, std::string help);
    Parser& flag(std::string name, std::string help);
    Parser& repeatable(std::string name, std::string value_name, std::string help);

    // Throws std::invalid_argument with a message naming the option.
    Parsed parse(int argc, char** argv) const;
    std::string help_text() const;
    // Prints the help or the version when asked for; true if the program should exit.
    bool answered_help_or_version(const Parsed& parsed, const char* version) const;

private:
    std::string program_, usage_, description_;
    std::vector<OptionSpec> options_;
};

// A program's main: `parse` returns the options (or nothing after --help/--version) and
// throws std::invalid_argument for bad usage (exit 2); `run` does the work and throws
// anything else for failures (exit 1). Messages read "PROGRAM: error: reason".
template <class Parse, class Run>
int run_program(const char* program, Parse parse, Run run) {
    decltype(parse()) options;
    try {
        options = parse();
        if (!options) return 0;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
        return 2;
    }
    try {
        return run(*options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
        return 1;
    }
}

// Parses a whole string as a number; throws std::invalid_argument naming `what`.
int parse_int(const std::string& text, const std::string& what, int min, int max);
double parse_double(const std::string& text, const std::string& what);

// --brdf gltf|thesis: the model named, or `fallback` without the option; throws
// std::invalid_argument naming the option and the choices.
BrdfModel brdf_option(const Parsed& args, BrdfModel fallback);

}  // namespace facet::cli
