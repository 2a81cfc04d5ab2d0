#include "scene/scene_line.h"

#include "core/error.h"

namespace vkray {

SceneLine::SceneLine(const std::string& file, int number, std::vector<Token> tokens)
    : file_(file), number_(number), tokens_(std::move(tokens)) {}

std::string SceneLine::argName(size_t arg) const {
    return "argument " + std::to_string(arg) + " of '" + std::string(command()) + "'";
}

void SceneLine::fail(const std::string& what, size_t arg) const {
    const int col = arg < tokens_.size() ? tokens_[arg].col : tokens_[0].col;
    throw Error(FileLoc{file_, number_, col}, what);
}

template <class T>
T SceneLine::parsed(size_t arg, NumberStatus (*parse)(std::string_view, T&), const char* noun) const {
    T value{};
    const NumberStatus status = parse(text(arg), value);
    if (status != NumberStatus::Ok) fail(describeNumberError(status, text(arg), argName(arg), noun), arg);
    return value;
}

float SceneLine::number(size_t arg) const { return parsed<float>(arg, parseFloat, "a number"); }
double SceneLine::real(size_t arg) const { return parsed<double>(arg, parseReal, "a number"); }
int64_t SceneLine::integer(size_t arg) const { return parsed<int64_t>(arg, parseInt, "an integer"); }

glm::vec3 SceneLine::vec3(size_t firstArg) const {
    return glm::vec3(number(firstArg), number(firstArg + 1), number(firstArg + 2));
}

glm::dvec3 SceneLine::dvec3(size_t firstArg) const {
    return glm::dvec3(real(firstArg), real(firstArg + 1), real(firstArg + 2));
}

}  // namespace vkray
