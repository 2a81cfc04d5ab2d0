#include "scene/ply_format.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cfloat>
#include <cstring>
#include <optional>

#include "scene/text_input.h"

namespace vkray::ply {
namespace {

struct TypeName {
    std::string_view name;
    Type type;
};

// Both spellings of the format's description: the original names and the sized ones.
constexpr TypeName kPlyTypeNames[] = {
    {"char", Type::Int8},     {"int8", Type::Int8},       {"uchar", Type::UInt8},     {"uint8", Type::UInt8},
    {"short", Type::Int16},   {"int16", Type::Int16},     {"ushort", Type::UInt16},   {"uint16", Type::UInt16},
    {"int", Type::Int32},     {"int32", Type::Int32},     {"uint", Type::UInt32},     {"uint32", Type::UInt32},
    {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64},
};

std::optional<Type> plyTypeOf(std::string_view name) {
    for (const TypeName& t : kPlyTypeNames)
        if (t.name == name) return t.type;
    return std::nullopt;
}

// The least bytes one element takes in the body: in binary its scalars and list lengths (a list
// may be empty), in ASCII one digit and one separator a value.
uint64_t minElementBytes(const Element& e, Encoding encoding) {
    uint64_t bytes = 0;
    for (const Property& p : e.properties)
        bytes += encoding == Encoding::Ascii ? 2 : sizeOf(p.list ? p.countType : p.type);
    return bytes;
}

class HeaderParser {
public:
    HeaderParser(std::string_view bytes, const std::string& displayName, const std::string& context)
        : bytes_(bytes), displayName_(displayName), context_(context) {}

    Header parse();

private:
    [[noreturn]] void fail(int col, const std::string& what) const {
        throw Error(FileLoc{displayName_, line_, col}, what + context_);
    }
    void format();
    void element();
    void property();
    Type type(size_t i) const;
    void checkCounts(size_t dataBytes) const;

    std::string_view bytes_;
    const std::string& displayName_;
    const std::string& context_;
    Header header_;
    bool hasFormat_ = false;
    int line_ = 0;
    std::vector<Token> t_;
};

Header HeaderParser::parse() {
    size_t pos = 0;
    while (pos < bytes_.size()) {
        const size_t eol = bytes_.find('\n', pos);
        std::string_view text = bytes_.substr(pos, eol == std::string_view::npos ? std::string_view::npos : eol - pos);
        if (text.ends_with('\r')) text.remove_suffix(1);
        ++line_;
        pos = eol == std::string_view::npos ? bytes_.size() : eol + 1;
        if (line_ == 1) {
            if (text != "ply") fail(1, "not a PLY file: the first line is not 'ply'");
            continue;
        }
        const std::string_view key = firstToken(text);
        if (key == "comment" || key == "obj_info") continue;
        tokenize(text, t_);
        if (t_.empty()) fail(1, "blank line in the PLY header");
        if (key == "format") {
            format();
        } else if (key == "element") {
            element();
        } else if (key == "property") {
            property();
        } else if (key == "end_header") {
            if (t_.size() > 1) fail(t_[1].col, "unexpected " + vkray::quoted(t_[1].text) + " after 'end_header'");
            if (!hasFormat_) fail(1, "the PLY header has no 'format' line");
            header_.dataOffset = pos;
            header_.dataLine = line_ + 1;
            checkCounts(bytes_.size() - pos);
            return header_;
        } else if (header_.strayLines++ == 0) {
            header_.firstStrayLine = line_;
        }
    }
    if (line_ == 0) fail(0, "not a PLY file: it is empty");
    fail(0, "the PLY header has no 'end_header' line");
}

void HeaderParser::format() {
    if (hasFormat_) fail(t_[0].col, "a second 'format' line");
    if (t_.size() != 3) fail(t_[0].col, "expected 'format ENCODING 1.0'");
    const std::string_view e = t_[1].text;
    if (e == "ascii")
        header_.encoding = Encoding::Ascii;
    else if (e == "binary_little_endian")
        header_.encoding = Encoding::BinaryLittleEndian;
    else if (e == "binary_big_endian")
        header_.encoding = Encoding::BinaryBigEndian;
    else
        fail(t_[1].col, "unknown PLY format " + vkray::quoted(e) + " (expected ascii, binary_little_endian or binary_big_endian)");
    if (t_[2].text != "1.0" && t_[2].text != "1") fail(t_[2].col, "unsupported PLY version " + vkray::quoted(t_[2].text) + " (vkray reads 1.0)");
    hasFormat_ = true;
}

void HeaderParser::element() {
    if (t_.size() != 3) fail(t_[0].col, "expected 'element NAME COUNT'");
    for (const Element& e : header_.elements)
        if (e.name == t_[1].text) fail(t_[1].col, "a second element " + vkray::quoted(e.name) + " (the first at line " + std::to_string(e.line) + ")");
    int64_t count = 0;
    if (parseInt(t_[2].text, count) != NumberStatus::Ok || count < 0)
        fail(t_[2].col, "the count of element " + vkray::quoted(t_[1].text) + " is not a non-negative integer: " + vkray::quoted(t_[2].text));
    header_.elements.push_back(Element{std::string(t_[1].text), count, {}, line_});
}

Type HeaderParser::type(size_t i) const {
    const std::optional<Type> t = plyTypeOf(t_[i].text);
    if (!t) fail(t_[i].col, "unknown PLY property type " + vkray::quoted(t_[i].text) + " (expected char, uchar, short, ushort, int, uint, float, double or int8 ... float64)");
    return *t;
}

void HeaderParser::property() {
    if (header_.elements.empty()) fail(t_[0].col, "'property' before any 'element'");
    Element& e = header_.elements.back();
    Property p;
    p.line = line_;
    size_t nameAt = 2;
    if (t_.size() > 1 && t_[1].text == "list") {
        if (t_.size() != 5) fail(t_[0].col, "expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
        p.list = true;
        p.countType = type(2);
        if (!isInteger(p.countType)) fail(t_[2].col, "a list's length type must be an integer type, not " + vkray::quoted(t_[2].text));
        p.type = type(3);
        nameAt = 4;
    } else {
        if (t_.size() != 3) fail(t_[0].col, "expected 'property TYPE NAME'");
        p.type = type(1);
    }
    p.name = std::string(t_[nameAt].text);
    if (e.find(p.name) >= 0) fail(t_[nameAt].col, "element " + vkray::quoted(e.name) + " has a second property " + vkray::quoted(p.name));
    e.properties.push_back(std::move(p));
}

void HeaderParser::checkCounts(size_t dataBytes) const {
    // An ASCII body may end without a separator after its last value.
    uint64_t left = header_.encoding == Encoding::Ascii ? dataBytes + 1 : dataBytes;
    for (const Element& e : header_.elements) {
        const uint64_t each = minElementBytes(e, header_.encoding);
        if (each == 0) continue;
        if (uint64_t(e.count) > left / each)
            throw Error(FileLoc{displayName_, e.line, 0},
                        std::to_string(e.count) + " elements " + vkray::quoted(e.name) + " of at least " +
                            std::to_string(each) + " bytes each cannot fit in the " + std::to_string(dataBytes) +
                            " bytes after the header" + context_);
        left -= uint64_t(e.count) * each;
    }
}

// A value of an integer type in range, or nothing.
bool inRange(int64_t v, Type t) {
    switch (t) {
        case Type::Int8: return v >= INT8_MIN && v <= INT8_MAX;
        case Type::UInt8: return v >= 0 && v <= UINT8_MAX;
        case Type::Int16: return v >= INT16_MIN && v <= INT16_MAX;
        case Type::UInt16: return v >= 0 && v <= UINT16_MAX;
        case Type::Int32: return v >= INT32_MIN && v <= INT32_MAX;
        case Type::UInt32: return v >= 0 && v <= int64_t(UINT32_MAX);
        default: return true;
    }
}

template <class T>
T loadAs(const char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

// The value of `t` at p, whose bytes are in the host's order.
double decode(const char* p, Type t) {
    switch (t) {
        case Type::Int8: return loadAs<int8_t>(p);
        case Type::UInt8: return loadAs<uint8_t>(p);
        case Type::Int16: return loadAs<int16_t>(p);
        case Type::UInt16: return loadAs<uint16_t>(p);
        case Type::Int32: return loadAs<int32_t>(p);
        case Type::UInt32: return loadAs<uint32_t>(p);
        case Type::Float32: return loadAs<float>(p);
        case Type::Float64: return loadAs<double>(p);
    }
    return 0.0;
}

}  // namespace

size_t sizeOf(Type t) {
    switch (t) {
        case Type::Int8: case Type::UInt8: return 1;
        case Type::Int16: case Type::UInt16: return 2;
        case Type::Int32: case Type::UInt32: case Type::Float32: return 4;
        case Type::Float64: return 8;
    }
    return 0;
}

bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

double maxOf(Type t) {
    switch (t) {
        case Type::Int8: return INT8_MAX;
        case Type::UInt8: return UINT8_MAX;
        case Type::Int16: return INT16_MAX;
        case Type::UInt16: return UINT16_MAX;
        case Type::Int32: return INT32_MAX;
        case Type::UInt32: return UINT32_MAX;
        default: return 1.0;
    }
}

int Element::find(std::string_view n) const {
    for (size_t i = 0; i < properties.size(); ++i)
        if (properties[i].name == n) return int(i);
    return -1;
}

Header parseHeader(std::string_view bytes, const std::string& displayName, const std::string& context) {
    return HeaderParser(bytes, displayName, context).parse();
}

Body::Body(std::string_view bytes, const Header& header, std::string displayName, std::string context)
    : bytes_(bytes), encoding_(header.encoding), displayName_(std::move(displayName)), context_(std::move(context)),
      pos_(header.dataOffset), valueStart_(header.dataOffset), line_(header.dataLine), lineStart_(header.dataOffset) {}

std::string Body::where(bool nameProperty) const {
    std::string s;
    if (element_) s = vkray::quoted(element_->name) + " " + std::to_string(index_) + " of " + std::to_string(element_->count);
    if (property_ && nameProperty) s += ", property " + vkray::quoted(property_->name);
    return s;
}

void Body::fail(const std::string& what, bool nameProperty) const {
    const std::string at = where(nameProperty);
    const std::string message = (at.empty() ? "" : "element " + at + ": ") + what + context_;
    if (encoding_ == Encoding::Ascii) throw Error(FileLoc{displayName_, valueLine_, valueCol_}, message);
    throw Error(FileLoc{displayName_}, "byte " + std::to_string(valueStart_) + ": " + message);
}

std::string_view Body::token(const Property& p) {
    property_ = &p;
    while (pos_ < bytes_.size()) {
        const char c = bytes_[pos_];
        if (c == '\n') {
            ++line_;
            lineStart_ = pos_ + 1;
        } else if (c != ' ' && c != '\t' && c != '\r' && c != '\v' && c != '\f') {
            break;
        }
        ++pos_;
    }
    valueStart_ = pos_;
    valueLine_ = line_;
    valueCol_ = int(pos_ - lineStart_) + 1;
    if (pos_ == bytes_.size()) fail("the file ends early");
    const size_t start = pos_;
    while (pos_ < bytes_.size() && !std::strchr(" \t\r\n\v\f", bytes_[pos_])) ++pos_;
    return bytes_.substr(start, pos_ - start);
}

double Body::value(const Property& p, Type type) {
    if (encoding_ == Encoding::Ascii) {
        const std::string_view s = token(p);
        if (isInteger(type)) {
            int64_t v = 0;
            const NumberStatus status = parseInt(s, v);
            if (status != NumberStatus::Ok) fail(describeNumberError(status, s, "the value", "an integer"));
            if (!inRange(v, type)) fail("the value " + excerpt(s) + " is out of its type's range");
            return double(v);
        }
        double v = 0.0;
        if (type == Type::Float64) {
            // A double may exceed the float range of parseReal; the loader checks the values it keeps.
            const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
            if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
                fail("expected a finite number for the value, got " + vkray::quoted(s));
            return v;
        }
        const NumberStatus status = parseReal(s, v);
        if (status != NumberStatus::Ok) fail(describeNumberError(status, s, "the value", "a number"));
        return type == Type::Float32 ? double(float(v)) : v;
    }
    property_ = &p;
    valueStart_ = pos_;
    const size_t n = sizeOf(type);
    if (bytes_.size() - pos_ < n) fail("the file ends early (" + std::to_string(bytes_.size()) + " bytes)");
    char raw[8];
    std::memcpy(raw, bytes_.data() + pos_, n);
    pos_ += n;
    const bool swap = (encoding_ == Encoding::BinaryBigEndian) == (std::endian::native == std::endian::little);
    if (swap) std::reverse(raw, raw + n);
    return decode(raw, type);
}

int64_t Body::listLength(const Property& p) {
    const double n = value(p, p.countType);
    if (n < 0) fail("a list of negative length " + std::to_string(int64_t(n)));
    const uint64_t itemBytes = encoding_ == Encoding::Ascii ? 2 : sizeOf(p.type);
    // + 1: an ASCII body may end without a separator after its last value.
    if (uint64_t(n) > (bytes_.size() - pos_ + 1) / itemBytes)
        fail("a list of " + std::to_string(int64_t(n)) + " items does not fit in the " +
             std::to_string(bytes_.size() - pos_) + " bytes left in the file");
    return int64_t(n);
}

void Body::skip(const Element& element) {
    const bool fixed = std::none_of(element.properties.begin(), element.properties.end(), [](const Property& p) { return p.list; });
    if (encoding_ != Encoding::Ascii && fixed) {
        // parseHeader checked the counts against the body at each element's least size, but a list
        // before this element may have taken more than its least: check what is left.
        const uint64_t each = minElementBytes(element, encoding_);
        element_ = nullptr;  // the message names the element itself, not the last value read
        property_ = nullptr;
        valueStart_ = pos_;
        if (each > 0 && uint64_t(element.count) > (bytes_.size() - pos_) / each)
            fail(std::to_string(element.count) + " elements " + vkray::quoted(element.name) + " of " +
                 std::to_string(each) + " bytes each do not fit in the " + std::to_string(bytes_.size() - pos_) +
                 " bytes left in the file");
        pos_ += size_t(uint64_t(element.count) * each);
        return;
    }
    if (element.properties.empty()) return;
    for (int64_t i = 0; i < element.count; ++i) {
        begin(element, i);
        for (const Property& p : element.properties) {
            const int64_t n = p.list ? listLength(p) : 1;
            for (int64_t k = 0; k < n; ++k) value(p, p.type);
        }
    }
    element_ = nullptr;
    property_ = nullptr;
}

void Body::finish() {
    element_ = nullptr;
    property_ = nullptr;
    if (encoding_ == Encoding::Ascii) {
        const size_t end = bytes_.find_first_not_of(" \t\r\n\v\f", pos_);
        if (end == std::string_view::npos) return;
        Property after;
        after.name = "";
        const std::string_view s = token(after);
        property_ = nullptr;
        fail("unexpected " + vkray::quoted(s) + " after the last element");
    }
    valueStart_ = pos_;
    if (pos_ != bytes_.size())
        fail(std::to_string(bytes_.size() - pos_) + " bytes after the last element (the header's counts are too small)");
}

}  // namespace vkray::ply
