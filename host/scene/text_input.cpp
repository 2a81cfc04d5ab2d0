#include "scene/text_input.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

#include "core/error.h"

namespace vkray {
namespace {

std::string hexByte(unsigned char c) {
    const char* digits = "0123456789ABCDEF";
    return std::string("0x") + digits[c >> 4] + digits[c & 15];
}

bool isAllowedControl(unsigned char c) { return c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Length of the UTF-8 sequence starting at s[i], or 0 when it is invalid (overlong forms,
// surrogates and code points above U+10FFFF included), following RFC 3629's byte table.
size_t utf8SequenceLength(std::string_view s, size_t i) {
    const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = byte(i);
    size_t len = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (c >= 0xC2 && c <= 0xDF)
        len = 2;
    else if (c == 0xE0)
        len = 3, lo = 0xA0;
    else if (c == 0xED)
        len = 3, hi = 0x9F;
    else if (c >= 0xE1 && c <= 0xEF)
        len = 3;
    else if (c == 0xF0)
        len = 4, lo = 0x90;
    else if (c == 0xF4)
        len = 4, hi = 0x8F;
    else if (c >= 0xF1 && c <= 0xF3)
        len = 4;
    else
        return 0;
    if (i + len > s.size()) return 0;
    if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
    for (size_t k = 2; k < len; ++k)
        if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
    return len;
}

// Throws on the first byte of `line` that `check` does not allow.
void checkLine(std::string_view line, const std::string& displayName, int number, TextCheck check,
               const std::string& context) {
    if (check == TextCheck::NoNul) {  // memchr speed: OBJ files run to millions of lines
        const size_t nul = line.find('\0');
        if (nul != std::string_view::npos)
            throw Error(FileLoc{displayName, number, int(nul) + 1}, "binary data (NUL byte); expected a text file" + context);
        return;
    }
    for (size_t i = 0; i < line.size();) {
        const auto c = static_cast<unsigned char>(line[i]);
        const FileLoc loc{displayName, number, int(i) + 1};
        if (c == 0) throw Error(loc, "binary data (NUL byte); expected a text file" + context);
        if (c >= 0x20 && c < 0x7F) {
            ++i;
            continue;
        }
        if (c < 0x80) {
            if (!isAllowedControl(c))
                throw Error(loc, "binary data (control byte " + hexByte(c) + "); expected a text file" + context);
            ++i;
            continue;
        }
        const size_t len = utf8SequenceLength(line, i);
        if (len == 0)
            throw Error(
                loc, "binary data or invalid UTF-8 (byte " + hexByte(c) + "); save the file as UTF-8 text" + context);
        i += len;
    }
}

// UTF-16 without a byte-order mark: ASCII text with a NUL after (little-endian) or before
// (big-endian) each character. Two characters tell it from a binary file; otherwise the first NUL
// would be reported as binary data, which is true but not the useful answer.
bool looksLikeUtf16WithoutBom(std::string_view d) {
    if (d.size() < 4) return false;
    const auto nul = [&](size_t i) { return d[i] == '\0'; };
    const auto text = [&](size_t i) {
        const auto c = static_cast<unsigned char>(d[i]);
        return (c >= 0x20 && c < 0x7F) || c == '\t' || c == '\n' || c == '\r';
    };
    return (text(0) && nul(1) && text(2) && nul(3)) || (nul(0) && text(1) && nul(2) && text(3));
}

std::string lowerFirst(std::string s) {
    if (!s.empty()) s[0] = char(std::tolower(static_cast<unsigned char>(s[0])));
    return s;
}

std::string tooLarge(uint64_t bytes) {
    return "is " + std::to_string(bytes) + " bytes, more than the " + std::to_string(kMaxInputFileBytes) +
           " (2 GiB) vkray reads";
}

// `s`, or its first bytes and its length, between `quote`s, control bytes escaped.
std::string shortened(std::string_view s, size_t maxBytes, std::string_view quote) {
    // Built with append: GCC 12 warns falsely (-Wrestrict) on chains of std::string operator+.
    std::string q(quote);
    if (s.size() <= maxBytes) return q.append(escapedControls(s)).append(quote);
    size_t cut = maxBytes;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
    q.append(escapedControls(s.substr(0, cut))).append("...").append(quote);
    return q.append(" (").append(std::to_string(s.size())).append(" bytes)");
}

// A pipe (or anything without a size): read in chunks up to the limit.
std::optional<std::string> readStream(std::istream& in, std::string& whyNot) {
    std::string bytes;
    char chunk[1 << 16];
    while (in) {
        in.read(chunk, sizeof chunk);
        bytes.append(chunk, size_t(in.gcount()));
        if (bytes.size() > kMaxInputFileBytes) {
            whyNot = "is larger than the " + std::to_string(kMaxInputFileBytes) + " bytes (2 GiB) vkray reads";
            return std::nullopt;
        }
    }
    if (in.bad()) {
        whyNot = "read error";
        return std::nullopt;
    }
    return bytes;
}

}  // namespace

std::optional<std::string> readFileBytes(const std::filesystem::path& file, std::string& whyNot) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(file, ec);  // follows symbolic links
    switch (status.type()) {
        case fs::file_type::not_found:
            whyNot = "no such file or directory";
            return std::nullopt;
        case fs::file_type::none:
            whyNot = lowerFirst(ec.message());  // a symbolic link loop, a path through a non-directory
            return std::nullopt;
        case fs::file_type::directory:
            whyNot = "is a directory";
            return std::nullopt;
        case fs::file_type::regular:
        case fs::file_type::fifo:
            break;
        case fs::file_type::character:
            whyNot = "is a character device, not a regular file";
            return std::nullopt;
        case fs::file_type::block:
            whyNot = "is a block device, not a regular file";
            return std::nullopt;
        default:
            whyNot = "is not a regular file";
            return std::nullopt;
    }
    errno = 0;
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        whyNot = errno != 0 ? lowerFirst(std::generic_category().message(errno)) : "cannot be opened";
        return std::nullopt;
    }
    if (status.type() == fs::file_type::fifo) return readStream(in, whyNot);
    const uintmax_t size = fs::file_size(file, ec);
    if (ec) {
        whyNot = lowerFirst(ec.message());
        return std::nullopt;
    }
    if (size > kMaxInputFileBytes) {
        whyNot = tooLarge(size);
        return std::nullopt;
    }
    std::string bytes(size_t(size), '\0');
    if (!in.read(bytes.data(), std::streamsize(size))) {
        whyNot = "read error (the file shrank while it was read?)";
        return std::nullopt;
    }
    // A file that grew meanwhile (or a /proc file that reports size 0): read the rest as a stream.
    if (in.peek() != std::char_traits<char>::eof()) {
        const std::optional<std::string> rest = readStream(in, whyNot);
        if (!rest) return std::nullopt;
        bytes += *rest;
        if (bytes.size() > kMaxInputFileBytes) {
            whyNot = tooLarge(bytes.size());
            return std::nullopt;
        }
    }
    return bytes;
}

std::optional<std::string> readFileBytes(const std::filesystem::path& file) {
    std::string whyNot;
    return readFileBytes(file, whyNot);
}

FileReader fileSystemReader() {
    return [](const std::filesystem::path& file, std::string& whyNot) { return readFileBytes(file, whyNot); };
}

std::string escapedControls(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (u >= 0x20 && u != 0x7F) {
            out += c;
        } else if (c == '\n' || c == '\r' || c == '\t') {
            out.append(c == '\n' ? "\\n" : c == '\r' ? "\\r" : "\\t");
        } else {
            static constexpr char kHex[] = "0123456789abcdef";
            out.append("\\x").append(1, kHex[u >> 4]).append(1, kHex[u & 15]);
        }
    }
    return out;
}

std::string quoted(std::string_view s, size_t maxBytes) { return shortened(s, maxBytes, "'"); }
std::string excerpt(std::string_view s, size_t maxBytes) { return shortened(s, maxBytes, ""); }

std::string_view withoutUtf8Bom(std::string_view s) {
    return s.substr(0, 3) == "\xEF\xBB\xBF" ? s.substr(3) : s;
}

void forEachLine(std::string_view data, const std::string& displayName, TextCheck check,
                 const std::function<void(std::string_view line, int number)>& fn, const std::string& context,
                 size_t maxLineBytes) {
    if (data.size() >= 2 &&
        ((data[0] == '\xFF' && data[1] == '\xFE') || (data[0] == '\xFE' && data[1] == '\xFF')))
        throw Error(FileLoc{displayName, 1}, "UTF-16 is not supported; save as UTF-8" + context);
    if (looksLikeUtf16WithoutBom(data))
        throw Error(FileLoc{displayName, 1},
                    "UTF-16 is not supported (no byte-order mark, but every other byte is NUL); save as UTF-8" +
                        context);
    data = withoutUtf8Bom(data);
    int number = 0;
    while (!data.empty()) {
        const size_t end = data.find('\n');
        std::string_view line = data.substr(0, end);
        data.remove_prefix(end == std::string_view::npos ? data.size() : end + 1);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        ++number;
        if (line.size() > maxLineBytes)
            throw Error(FileLoc{displayName, number}, "line is " + std::to_string(line.size()) +
                                                          " bytes long, more than the " +
                                                          std::to_string(maxLineBytes) + " a line may have" +
                                                          context);
        checkLine(line, displayName, number, check, context);
        fn(line, number);
    }
}

namespace {
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

void tokenize(std::string_view line, std::vector<Token>& tokens) {
    tokens.clear();
    size_t i = 0;
    while (i < line.size()) {
        if (isSpace(line[i])) {
            ++i;
            continue;
        }
        if (line[i] == '#') break;
        const size_t start = i;
        while (i < line.size() && !isSpace(line[i]) && line[i] != '#') ++i;
        tokens.push_back({line.substr(start, i - start), int(start) + 1});
    }
}

std::vector<Token> tokenize(std::string_view line) {
    std::vector<Token> tokens;
    tokenize(line, tokens);
    return tokens;
}

std::string_view firstToken(std::string_view line) {
    size_t i = 0;
    while (i < line.size() && isSpace(line[i])) ++i;
    size_t end = i;
    while (end < line.size() && !isSpace(line[end]) && line[end] != '#') ++end;
    return line.substr(i, end - i);
}

NumberStatus parseReal(std::string_view s, double& out) {
    // std::from_chars is locale-independent and reports overflow, unlike strtof under a
    // German locale; it rejects a leading '+', which strtod (and CSE167 files) accept.
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || end != s.data() + s.size()) return NumberStatus::NotANumber;
    // Overflow and underflow of a double alike (1e999, 1e-999): no scene means either.
    if (ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
    if (ec != std::errc()) return NumberStatus::NotANumber;
    if (!std::isfinite(value)) return NumberStatus::NotFinite;
    if (std::abs(value) > double(std::numeric_limits<float>::max())) return NumberStatus::OutOfRange;
    out = value;
    return NumberStatus::Ok;
}

NumberStatus parseFloat(std::string_view s, float& out) {
    double value = 0.0;
    const NumberStatus status = parseReal(s, value);
    if (status == NumberStatus::Ok) out = static_cast<float>(value);
    return status;
}

NumberStatus parseInt(std::string_view s, int64_t& out) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
    int64_t value = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || end != s.data() + s.size()) return NumberStatus::NotANumber;
    if (ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
    if (ec != std::errc()) return NumberStatus::NotANumber;
    out = value;
    return NumberStatus::Ok;
}

std::string describeNumberError(NumberStatus status, std::string_view tokenText, const std::string& what,
                                std::string_view kind) {
    // Built with append: GCC 12 warns falsely (-Wrestrict) on chains of std::string operator+.
    const std::string token = quoted(tokenText);
    std::string msg;
    switch (status) {
        case NumberStatus::NotFinite:
            msg.append(what).append(" is ").append(token).append(", not a finite number");
            return msg;
        case NumberStatus::OutOfRange:
            msg.append(what).append(" ").append(token).append(" is out of range");
            if (kind != "an integer") msg.append(" for a 32-bit float");
            return msg;
        case NumberStatus::NotANumber:
        case NumberStatus::Ok:
            break;
    }
    msg.append("expected ").append(kind).append(" for ").append(what).append(", got ").append(token);
    return msg;
}

std::optional<std::vector<double>> parseRealList(std::string_view text) {
    const bool commas = text.find(',') != std::string_view::npos;
    std::vector<double> out;
    if (!commas) {  // whitespace-separated (one item when there is none)
        for (const Token& t : tokenize(text)) {
            double x = 0.0;
            if (parseReal(t.text, x) != NumberStatus::Ok) return std::nullopt;
            out.push_back(x);
        }
        if (out.empty() || text.find('#') != std::string_view::npos) return std::nullopt;
        return out;
    }
    for (size_t start = 0;;) {  // every comma-separated item, empty ones included
        const size_t comma = std::min(text.find(',', start), text.size());
        double x = 0.0;
        if (parseReal(text.substr(start, comma - start), x) != NumberStatus::Ok) return std::nullopt;
        out.push_back(x);
        if (comma == text.size()) return out;
        start = comma + 1;
    }
}

std::optional<IndexOfCount> parseIndexOfCount(std::string_view text) {
    const size_t slash = text.find('/');
    const auto number = [](std::string_view digits) -> std::optional<int> {
        if (digits.empty() || digits.size() > 9 ||
            !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
            return std::nullopt;
        int v = 0;
        std::from_chars(digits.data(), digits.data() + digits.size(), v);
        return v;
    };
    if (slash == std::string_view::npos) return std::nullopt;
    const auto i = number(text.substr(0, slash)), n = number(text.substr(slash + 1));
    if (!i || !n) return std::nullopt;
    return IndexOfCount{*i, *n};
}

}  // namespace vkray
