#pragma once
// A small JSON writer for the metadata files (bake.json, NAME.json): objects, arrays,
// strings escaped per RFC 8259, numbers with enough digits to round-trip.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace facet {

class JsonWriter {
public:
    JsonWriter& begin_object(std::string_view key = {});
    JsonWriter& end_object();
    JsonWriter& begin_array(std::string_view key = {});
    JsonWriter& end_array();
    JsonWriter& value(std::string_view key, std::string_view text);
    JsonWriter& value(std::string_view key, const char* text) { return value(key, std::string_view(text)); }
    JsonWriter& value(std::string_view key, double number);
    JsonWriter& value(std::string_view key, int64_t number);
    JsonWriter& value(std::string_view key, uint32_t number) { return value(key, int64_t(number)); }
    JsonWriter& value(std::string_view key, int number) { return value(key, int64_t(number)); }
    JsonWriter& value(std::string_view key, bool flag);

    // The document, pretty-printed with two-space indents and a final newline.
    std::string str() const;

private:
    void key_prefix(std::string_view key);
    void newline_indent();
    std::string out_;
    std::vector<bool> first_;  // per open container: nothing written yet
};

std::string json_escape(std::string_view text);

}  // namespace facet
