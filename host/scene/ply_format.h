// The PLY file format itself (Turk, "The PLY Polygon File Format", 1994): its header, and its values
// read one by one from the ASCII or binary body, with every bound checked. What the values mean (a
// mesh) is ply_loader.cpp's business.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace vkray::ply {

enum class Type : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

size_t sizeOf(Type t);
bool isInteger(Type t);
// The largest value of an integer type (255 for uchar): what an integer colour is scaled by.
double maxOf(Type t);

struct Property {
    std::string name;
    Type type = Type::Float32;  // of the value, or of a list's items
    bool list = false;
    Type countType = Type::UInt8;  // of a list's length
    int line = 0;                  // in the header
};

struct Element {
    std::string name;
    int64_t count = 0;
    std::vector<Property> properties;
    int line = 0;  // in the header

    // Index of the property called `name`, or -1.
    int find(std::string_view name) const;
};

enum class Encoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
    Encoding encoding = Encoding::Ascii;
    std::vector<Element> elements;
    size_t dataOffset = 0;  // the first byte after the end_header line
    int dataLine = 0;       // the line the ASCII body starts on
    // Header lines with no PLY keyword, read past as comments (Blender 2.4x wrote "Created by
    // Blender ..." without `comment`): how many, and the first one's line.
    int strayLines = 0, firstStrayLine = 0;
};

// Reads the header of `bytes`. Throws vkray::Error at displayName:line:col, with `context` appended,
// for a file that does not start with the line "ply", an unknown format or type, a
// `property` before any `element`, a name used twice, a count that is not a non-negative integer,
// no `format` or no `end_header`, and element counts that the body cannot hold at the fewest bytes
// an element can take (so a header that lies about its counts reserves nothing).
Header parseHeader(std::string_view bytes, const std::string& displayName, const std::string& context);

// The body's values in file order. Each read names the element and property it is for, so that an
// error can say where it happened: "byte 1234: face 17 of 100, property 'vertex_indices': ...".
class Body {
public:
    Body(std::string_view bytes, const Header& header, std::string displayName, std::string context);

    // Before the values of element `index` of `element`.
    void begin(const Element& element, int64_t index) {
        element_ = &element;
        index_ = index;
    }
    // One scalar value of `p` (a list's items: `p` with its item type). A float32 is rounded to float
    // however it was written, so ASCII and binary files of the same floats read the same.
    double value(const Property& p, Type type);
    // A list's length, checked to be non-negative and, at the fewest bytes an item takes, to fit in
    // what is left of the file.
    int64_t listLength(const Property& p);
    // Reads past all of `element`'s values (every element of it), at once where they have a fixed size.
    void skip(const Element& element);
    // Throws unless the body ends here.
    void finish();

    // The error at the last value read, naming its element and (unless !nameProperty) its property.
    [[noreturn]] void fail(const std::string& what, bool nameProperty = true) const;

private:
    std::string_view token(const Property& p);
    std::string where(bool nameProperty) const;

    std::string_view bytes_;
    Encoding encoding_;
    std::string displayName_, context_;
    size_t pos_;
    size_t valueStart_;  // of the last value read
    int line_, valueLine_ = 0, valueCol_ = 0;
    size_t lineStart_;
    const Element* element_ = nullptr;
    int64_t index_ = 0;
    const Property* property_ = nullptr;
};

}  // namespace vkray::ply
