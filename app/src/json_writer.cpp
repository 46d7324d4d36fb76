#include "json_writer.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace app {

std::string EscapeJson(const std::string& text) {
    std::string out;
    for (unsigned char c : text) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            case '\r': out += "\\r"; break;
            default:
                if (c < 0x20) {
                    char buffer[8];
                    std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
                    out += buffer;
                } else {
                    out += static_cast<char>(c);
                }
        }
    }
    return out;
}

void JsonWriter::BeforeValue() {
    if (afterKey_) {
        afterKey_ = false;
        return;
    }
    if (!needsComma_.empty()) {
        if (needsComma_.back()) text_ += ",";
        needsComma_.back() = true;
    }
}

JsonWriter& JsonWriter::BeginObject() { BeforeValue(); text_ += "{"; needsComma_.push_back(false); return *this; }
JsonWriter& JsonWriter::EndObject() { needsComma_.pop_back(); text_ += "}"; return *this; }
JsonWriter& JsonWriter::BeginArray() { BeforeValue(); text_ += "["; needsComma_.push_back(false); return *this; }
JsonWriter& JsonWriter::EndArray() { needsComma_.pop_back(); text_ += "]"; return *this; }

JsonWriter& JsonWriter::Key(const std::string& key) {
    BeforeValue();
    text_ += "\"" + EscapeJson(key) + "\":";
    afterKey_ = true;
    return *this;
}

JsonWriter& JsonWriter::Number(double value) {
    if (!std::isfinite(value)) return Null();
    BeforeValue();
    // Shortest text that reads back as the same double: 4.1, not 4.0999999999999996.
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
    text_.append(buffer, end);
    return *this;
}

JsonWriter& JsonWriter::Integer(long long value) { BeforeValue(); text_ += std::to_string(value); return *this; }
JsonWriter& JsonWriter::String(const std::string& value) { BeforeValue(); text_ += "\"" + EscapeJson(value) + "\""; return *this; }
JsonWriter& JsonWriter::Bool(bool value) { BeforeValue(); text_ += value ? "true" : "false"; return *this; }
JsonWriter& JsonWriter::Null() { BeforeValue(); text_ += "null"; return *this; }

JsonWriter& JsonWriter::NumberArray(const std::vector<double>& values) {
    BeginArray();
    for (double v : values) Number(v);
    return EndArray();
}

}  // namespace app
