// stub.hpp — how an unfinished exercise fails politely.
//
// Every exercise function starts life as a stub whose body is
//
//     RT_NOT_IMPLEMENTED("chapter 01", "intersect_unit_sphere");
//
// which throws rt::not_implemented with the message
// "not implemented yet: chapter 01, intersect_unit_sphere". The tests report
// it as a failed test with that message, and the chapter programs print it
// and exit with status 3, so a stub is never a crash or a wrong picture.
#pragma once

#include <stdexcept>
#include <string>

namespace rt {

class not_implemented : public std::logic_error {
public:
    not_implemented(const std::string& chapter, const std::string& function)
        : std::logic_error("not implemented yet: " + chapter + ", " + function) {}
};

// Exit status of a chapter program that reached a stub.
inline constexpr int exit_not_implemented = 3;

}  // namespace rt

#define RT_NOT_IMPLEMENTED(chapter, function) throw ::rt::not_implemented((chapter), (function))
