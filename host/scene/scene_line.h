// One command line of a .scene file with typed access to its arguments. Every accessor throws
// vkray::Error at file:line:col of the offending token, with the command named in the message.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "scene/text_input.h"

namespace vkray {

class SceneLine {
public:
    // `tokens` is non-empty; tokens[0] is the command.
    SceneLine(const std::string& file, int number, std::vector<Token> tokens);

    std::string_view command() const { return tokens_[0].text; }
    size_t argCount() const { return tokens_.size() - 1; }
    int number() const { return number_; }
    const std::string& file() const { return file_; }

    // Arguments are 1-based, as in the messages ("argument 2 of 'vertex'").
    std::string_view text(size_t arg) const { return tokens_.at(arg).text; }
    float number(size_t arg) const;
    int64_t integer(size_t arg) const;
    glm::vec3 vec3(size_t firstArg) const;  // arguments firstArg .. firstArg + 2
    // The same in double (still within float's range), for positions and transforms a far scene
    // needs exactly: at 1e6 floats are 1/16 apart, doubles 1e-10, and Scene::origin takes the
    // offset off in double. number() is real() rounded to float.
    double real(size_t arg) const;
    glm::dvec3 dvec3(size_t firstArg) const;

    // Fails at argument `arg` (its column; 0 = the command itself).
    [[noreturn]] void fail(const std::string& what, size_t arg = 0) const;

private:
    std::string argName(size_t arg) const;
    // Argument `arg` read by `parse`; a failure names it as `noun` ("a number").
    template <class T>
    T parsed(size_t arg, NumberStatus (*parse)(std::string_view, T&), const char* noun) const;

    const std::string& file_;
    int number_;
    std::vector<Token> tokens_;
};

}  // namespace vkray
