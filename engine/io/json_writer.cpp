#include <facet/io/json_writer.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace facet {

std::string json_escape(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

void JsonWriter::newline_indent() {
    out_ += '\n';
    out_.append(first_.size() * 2, ' ');
}

void JsonWriter::key_prefix(std::string_view key) {
    if (!first_.empty()) {
        if (!first_.back()) out_ += ",";
        first_.back() = false;
        newline_indent();
    }
    if (!key.empty()) out_ += json_escape(key) + ": ";
}

JsonWriter& JsonWriter::begin_object(std::string_view key) {
    key_prefix(key);
    out_ += "{";
    first_.push_back(true);
    return *this;
}

JsonWriter& JsonWriter::end_object() {
    bool empty = first_.back();
    first_.pop_back();
    if (!empty) newline_indent();
    out_ += "}";
    return *this;
}

JsonWriter& JsonWriter::begin_array(std::string_view key) {
    key_prefix(key);
    out_ += "[";
    first_.push_back(true);
    return *this;
}

JsonWriter& JsonWriter::end_array() {
    bool empty = first_.back();
    first_.pop_back();
    if (!empty) newline_indent();
    out_ += "]";
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view key, std::string_view text) {
    key_prefix(key);
    out_ += json_escape(text);
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view key, double number) {
    key_prefix(key);
    if (!std::isfinite(number)) {
        out_ += "null";  // JSON has no NaN/Inf
        return *this;
    }
    // Shortest of 15 or 17 significant digits that reads back as the same double.
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", number);
    if (std::strtod(buf, nullptr) != number) std::snprintf(buf, sizeof buf, "%.17g", number);
    out_ += buf;
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view key, int64_t number) {
    key_prefix(key);
    out_ += std::to_string(number);
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view key, bool flag) {
    key_prefix(key);
    out_ += flag ? "true" : "false";
    return *this;
}

std::string JsonWriter::str() const { return out_ + "\n"; }

}  // namespace facet
