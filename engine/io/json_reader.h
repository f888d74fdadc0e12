#pragma once
// A small JSON reader (RFC 8259) for Facet's own metadata files (bake.json, sh9.json):
// the whole document into a tree of values. Enough for files Facet writes and a person
// may have edited; an error gives the line and column and what was expected.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <facet/core/result.h>

namespace facet {

class JsonValue {
public:
    enum class Type { null, boolean, number, string, array, object };

    Type type() const { return type_; }
    bool is_null() const { return type_ == Type::null; }
    bool is_number() const { return type_ == Type::number; }
    bool is_string() const { return type_ == Type::string; }
    bool is_array() const { return type_ == Type::array; }
    bool is_object() const { return type_ == Type::object; }

    double number() const { return number_; }
    bool boolean() const { return boolean_; }
    const std::string& string() const { return string_; }
    const std::vector<JsonValue>& items() const { return items_; }  // array elements
    const std::vector<std::pair<std::string, JsonValue>>& members() const { return members_; }
    // The member named `key` of an object (the first, if repeated); nullptr if absent or
    // this is not an object.
    const JsonValue* find(std::string_view key) const;

private:
    friend class JsonParser;
    Type type_ = Type::null;
    double number_ = 0;
    bool boolean_ = false;
    std::string string_;
    std::vector<JsonValue> items_;
    std::vector<std::pair<std::string, JsonValue>> members_;
};

// Parses a whole document (one value, whitespace around it); nesting deeper than 64 is
// refused, so a hostile file cannot exhaust the stack.
Result<JsonValue> parse_json(std::string_view text);

}  // namespace facet
