// Text input shared by the .scene parser and the OBJ/MTL checks: whole-file reads, encoding checks,
// line splitting, tokens with their columns, and locale-independent number parsing. One place, so
// every input file reports bad bytes and bad numbers the same way ("file:line:col: ...").
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vkray {

// Input files are at most this large: line numbers and columns are ints, and no file a scene
// needs comes close (the largest real mesh of scenes/ is 50 MB).
inline constexpr uint64_t kMaxInputFileBytes = (uint64_t(1) << 31) - 1;

// The whole file as bytes; nullopt when it cannot be read, with `whyNot` saying why ("no such file
// or directory", "is a directory", "is a character device, not a regular file", "is 3 GiB, ..."),
// so the caller can say which kind of file it wanted and who asked for it. Regular files and pipes
// are read; devices are refused (/dev/zero would never end).
std::optional<std::string> readFileBytes(const std::filesystem::path& file, std::string& whyNot);
std::optional<std::string> readFileBytes(const std::filesystem::path& file);

// How loaders get the bytes of the files a scene names (geo/obj meshes, MTL libraries): the file
// system by default; the fuzzer serves them from memory so that fuzzed input touches no real file.
using FileReader = std::function<std::optional<std::string>(const std::filesystem::path& file, std::string& whyNot)>;
// readFileBytes as a FileReader.
FileReader fileSystemReader();

// `s` quoted for an error message: 'text', or its first bytes and its length when it is long, so
// a 10 MB token makes a readable one-line message ('11111111...' (10000000 bytes)); control bytes
// are escaped ('a\nb', '\x01'), so the message stays one line whatever the file held.
std::string quoted(std::string_view s, size_t maxBytes = 48);
// `s` with its control bytes written as C escapes (\n, \t, \x01): text taken from a file (a glTF
// URI, a PNG chunk type in a decoder's message, an EXR channel name) may hold any byte, and an error
// message is one line.
std::string escapedControls(std::string_view s);
// The same without the quotes, for numbers: 1.5, or 0.00000000...1 (60000 bytes).
std::string excerpt(std::string_view s, size_t maxBytes = 48);

enum class TextCheck {
    Utf8,   // .scene files: valid UTF-8 without control bytes (except tab, CR, VT, FF)
    NoNul,  // OBJ/MTL files: exporters write Latin-1 comments, so only binary data is rejected
};

// `s` without a leading UTF-8 byte-order mark.
std::string_view withoutUtf8Bom(std::string_view s);

// Calls `fn(line, number)` for each line of `data` (1-based numbers, LF or CRLF endings, the
// terminator removed) after rejecting UTF-16 (with a byte-order mark, or ASCII text interleaved
// with NUL bytes) and skipping a UTF-8 BOM. Throws vkray::Error naming `displayName`:line on
// binary data, invalid UTF-8, or a line longer than `maxLineBytes`, with `context` appended to the
// message (" (OBJ loaded at a.scene:3)").
void forEachLine(std::string_view data, const std::string& displayName, TextCheck check,
                 const std::function<void(std::string_view line, int number)>& fn, const std::string& context = {},
                 size_t maxLineBytes = std::string_view::npos);

struct Token {
    std::string_view text;
    int col = 0;  // 1-based byte column in its line
};

// Whitespace-separated tokens of `line`, stopping at '#' (a comment runs to the end of the line).
std::vector<Token> tokenize(std::string_view line);
// The same into `out` (cleared first), reusing its storage: for files of millions of lines.
void tokenize(std::string_view line, std::vector<Token>& out);
// The first token of `line` (empty for a blank or comment line), without tokenizing the rest.
std::string_view firstToken(std::string_view line);

enum class NumberStatus { Ok, NotANumber, NotFinite, OutOfRange };

// The whole token must be a number (an optional leading '+' is accepted, as strtod does).
// Floats must be finite and fit a 32-bit float: "nan", "inf" and 1e999 are rejected.
NumberStatus parseFloat(std::string_view s, float& out);
// The same number kept in double (the same rule: it must fit a 32-bit float), for positions that a
// transform and the scene's local origin map before they are rounded to float once. parseFloat is
// this, rounded.
NumberStatus parseReal(std::string_view s, double& out);
NumberStatus parseInt(std::string_view s, int64_t& out);
// A list of numbers as a command-line value gives it: separated by commas ("1,2,3", every item a
// number, none empty) or by whitespace ("1 2 3", as one quoted argument); each by parseReal's rule.
// Nothing when any item is not such a number.
std::optional<std::vector<double>> parseRealList(std::string_view text);
// "I/N", one part of several (`render --tile`, `bench --shard`, a tile's `vkray:tile`): two whole
// numbers of digits alone, at most 1e9, with a slash between. Nothing when the text is not of that
// form; the caller checks that 0 <= I < N.
struct IndexOfCount {
    int index = 0, count = 1;
};
std::optional<IndexOfCount> parseIndexOfCount(std::string_view text);

// "expected a number for argument 2 of 'vertex', got 'abc'" and its siblings; `what` names the
// value ("argument 2 of 'vertex'") and `kind` what was expected ("a number", "an integer").
std::string describeNumberError(NumberStatus status, std::string_view token, const std::string& what,
                                std::string_view kind);

}  // namespace vkray
