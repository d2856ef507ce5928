// table_builds.hpp — what a chapter's table (tests/support/rpc/chNN.cpp) is made of.
//
// A table lists the chapter's exercise functions once, and is compiled in one of three ways:
//   RT_RPC_JUDGE        into the chapter's judges: each exercise function is a stub that forwards its
//                       arguments to the runner (RT_RPC_FORWARD) and returns the runner's answer;
//   RT_RPC_RUNNER       into the chapter's runner: each exercise function is registered by name, so a
//                       call runs the student's code;
//   RT_RPC_PLACEHOLDER  as the stand-in for an exercise file in the grader's tree of a student kit: each
//                       function throws, so the tree builds whatever state the student's files are in.
// RT_RPC_FUNCTION(namespace, name) does a function template's part for float and double. A call's name
// is RT_RPC_CHAPTER::name<float> (cmake/judge.cmake defines RT_RPC_CHAPTER as "chNN": chapter 08's
// closest_hit is not chapter 03's). The stubs'
// definitions sit in `#if RT_RPC_DEFINES_STUBS`.
#pragma once

#if defined(RT_RPC_JUDGE)

#include "judge_side.hpp"

#define RT_RPC_DEFINES_STUBS 1
// Inside the judge's definition of `name`: send the call, return the answer.
#define RT_RPC_FORWARD(name, ...) \
    ::rt::rpc::forward<decltype(name<T>(__VA_ARGS__))>(::rt::rpc::call_name<T>(RT_RPC_CHAPTER "::" #name), __VA_ARGS__)
// The same with the result type R given, for a call whose arguments are not the function's own (a
// served callback travels as its table, served_by_judge.hpp).
#define RT_RPC_FORWARD_AS(R, name, ...) \
    ::rt::rpc::forward<R>(::rt::rpc::call_name<T>(RT_RPC_CHAPTER "::" #name), __VA_ARGS__)
// A call that takes an object callback (chapter 03's closest_hit, chapter 08's traversal): the judge
// keeps `callback` (for the call's ray r) and the arguments name its stand-in `served`; once the call
// is over, the judge's record of the callback's calls decides (served_by_judge.hpp, judged_call).
#define RT_RPC_FORWARD_SERVED(R, name, callback, r, ...)                                                      \
    ::rt::rpc::judged_call<R>(callback, r, [&](const auto& served) {                                          \
        return ::rt::rpc::forward<R>(::rt::rpc::call_name<T>(RT_RPC_CHAPTER "::" #name), __VA_ARGS__);        \
    })

#elif defined(RT_RPC_PLACEHOLDER)

#include <stdexcept>
#include <string>

namespace rt::rpc {
template <class R, class... A>
[[noreturn]] R placeholder(const char* name, const A&...) {
    throw std::logic_error(std::string(name) + " is missing: this chapter's exercise file was not compiled here "
                                               "(the grader grades it from your submission)");
}
}  // namespace rt::rpc

#define RT_RPC_DEFINES_STUBS 1
#define RT_RPC_FORWARD(name, ...) ::rt::rpc::placeholder<decltype(name<T>(__VA_ARGS__))>(#name, __VA_ARGS__)
#define RT_RPC_FORWARD_AS(R, name, ...) ::rt::rpc::placeholder<R>(#name)  // the arguments are not evaluated
#define RT_RPC_FORWARD_SERVED(R, name, ...) ::rt::rpc::placeholder<R>(#name)

#elif defined(RT_RPC_RUNNER)

#include "runner_side.hpp"

#define RT_RPC_DEFINES_STUBS 0
#define RT_RPC_FUNCTION(ns, name)                                                                  \
    static const bool rt_rpc_served_##name =                                                       \
        ::rt::rpc::serve(RT_RPC_CHAPTER "::" #name "<float>", &ns::name<float>) &&                  \
        ::rt::rpc::serve(RT_RPC_CHAPTER "::" #name "<double>", &ns::name<double>);

#else
#error "compile a chapter's RPC table with RT_RPC_JUDGE, RT_RPC_RUNNER or RT_RPC_PLACEHOLDER (cmake/judge.cmake)"
#endif

#if RT_RPC_DEFINES_STUBS && defined(RT_RPC_PLACEHOLDER)
// Emits the stand-ins for float, double and long double: the chapter's program links them too,
// and chapter 07's program measures its error against its own test in long double.
#define RT_RPC_FUNCTION(ns, name)                                                 \
    [[gnu::used]] static auto* const rt_rpc_float_##name = &ns::name<float>;      \
    [[gnu::used]] static auto* const rt_rpc_double_##name = &ns::name<double>;    \
    [[gnu::used]] static auto* const rt_rpc_long_double_##name = &ns::name<long double>;
#elif RT_RPC_DEFINES_STUBS
// Emits the stubs for float and double (what the tests link against).
#define RT_RPC_FUNCTION(ns, name)                                            \
    [[gnu::used]] static auto* const rt_rpc_float_##name = &ns::name<float>; \
    [[gnu::used]] static auto* const rt_rpc_double_##name = &ns::name<double>;
#endif
