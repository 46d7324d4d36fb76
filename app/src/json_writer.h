// A minimal JSON writer for results: numbers at round-trip precision, non-finite numbers as null
// (JSON has no NaN), strings escaped. Commas are placed automatically.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace app {

class JsonWriter {
public:
    JsonWriter& BeginObject();
    JsonWriter& EndObject();
    JsonWriter& BeginArray();
    JsonWriter& EndArray();
    JsonWriter& Key(const std::string& key);
    JsonWriter& Number(double value);
    JsonWriter& Integer(long long value);
    JsonWriter& String(const std::string& value);
    JsonWriter& Bool(bool value);
    JsonWriter& Null();
    JsonWriter& NumberArray(const std::vector<double>& values);

    const std::string& Text() const { return text_; }

private:
    void BeforeValue();
    std::string text_;
    std::vector<bool> needsComma_;  // one per open container
    bool afterKey_ = false;
};

std::string EscapeJson(const std::string& text);

}  // namespace app
