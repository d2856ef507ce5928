// served_by_judge.hpp — how the tests' callbacks travel (served.hpp says what they are and which rules they check).
//
// Chapter 03's intersector and chapter 08's leaf test: the judge answers every call. Its stub keeps the
// test's callback IN THE JUDGE, in an object_server with the test's rules (budget, expected calls); the
// runner gets a function that sends each call's arguments to the judge and returns the judge's answer.
// When the exercise's call is over, the stub asks the server's record whether a rule broke and throws
// broken_rule if one did (judged_call), whatever the runner answered. Nothing is answered from data in
// the runner: whatever the runner holds, the student's code can read (the red team's closest_hit read a
// table of every object's hits through std::function::target and scored 86/90 without a loop), and how
// the code uses the callback (order, shrinking tmax, pruning) is only known to the judge if the judge
// sees the calls. Nor is a rule reported inside an answer: the student's code can read an answer
// before it hands it back (a "fault record" in the answer was skipped by a loop that knew its shape).
//
// Chapter 06's occlusion test goes the same way: the judge keeps the answers to the questions shade()
// may ask and answers each question the runner sends. A question off the list or over the budget is
// noted in the judge, and the judge's stub throws std::logic_error out of shade() after the call: an
// exception thrown inside the runner could be caught there by the student's own shade().
#pragma once

#include "served.hpp"
#include "exact_bits.hpp"

#if defined(RT_RPC_JUDGE)
#include "judge_side.hpp"
#endif

#include <memory>
#include <stdexcept>

namespace rt::rpc {

// Judge side: what an object callback argument becomes for one call of the exercise, the server of the
// test's callback for the call's ray. put() registers it with the call (judge_side.cpp keeps it until the
// call's answer) and sends only its number. A callback that is not rt::test::served_objects cannot be
// answered by the grader: a test error.
template <class T>
struct judge_callback {
    std::shared_ptr<test::object_server<T>> server;
};

template <class T, class Callback>
judge_callback<T> judge_served(const Callback& f, const ray<T>& r) {
    const auto* served = f.template target<test::served_objects<T>>();
    if (served == nullptr)
        throw std::logic_error("a test gave a callback that is not rt::test::served_objects "
                               "(tests/support/rpc/served.hpp): the grader cannot answer it");
    return {std::make_shared<test::object_server<T>>(served->server_for(r))};
}

#if defined(RT_RPC_JUDGE)
// One call of an exercise that takes an object callback, made by the judge's stub: `send(callback)`
// forwards the call with the callback's number (RT_RPC_FORWARD_SERVED, table_builds.hpp). Once it is over, the
// record of the calls the judge served decides: a broken rule throws broken_rule (with the call's
// numbers in a public judge, the rule alone in a hidden one), whatever the runner answered or threw.
template <class R, class T, class Callback, class Send>
R judged_call(const Callback& f, const ray<T>& r, Send&& send) {
    const judge_callback<T> served = judge_served(f, r);
    R answer{};
    try {
        answer = send(served);
    } catch (const runner_gone&) {
        throw;  // the runner broke: that fails the case already
    } catch (...) {
        served.server->throw_if_broken(public_feedback);
        throw;
    }
    served.server->throw_if_broken(public_feedback);
    return answer;
}
#endif

template <class T>
void put(writer& w, const judge_callback<T>& c) {
    put(w, judge_keep_callback([server = c.server](reader& in, writer& out) {
        int i = 0;
        ray<T> r{};
        interval<T> range{};
        get(in, i);
        get(in, r);
        get(in, range);
        put(out, server->answer(i, r, range));
    }));
}

// Runner side: the student's code calls this; it asks the judge.
template <class T>
std::optional<hit_record<T>> ask_judge(std::uint32_t id, int i, const ray<T>& r, const interval<T>& range) {
    writer arguments;
    put(arguments, i);
    put(arguments, r);
    put(arguments, range);
    const std::string answer = runner_call_back(id, arguments.bytes());
    reader in(answer);
    std::optional<hit_record<T>> hit;
    get(in, hit);
    return hit;
}

template <class T>
void get(reader& r, std::function<std::optional<hit_record<T>>(int, const ray<T>&, const interval<T>&)>& f) {
    std::uint32_t id = 0;
    get(r, id);
    f = [id](int i, const ray<T>& ray_, const interval<T>& range) { return ask_judge(id, i, ray_, range); };
}
template <class T>
void get(reader& r, std::function<bool(int, const ray<T>&, const interval<T>&, hit_record<T>&)>& f) {
    std::uint32_t id = 0;
    get(r, id);
    f = [id](int i, const ray<T>& ray_, const interval<T>& range, hit_record<T>& hit) {
        return test::served_objects<T>::fill(ask_judge(id, i, ray_, range), i, hit);
    };
}

// Chapter 06, judge side: the occlusion answers of one call of shade(), and the first rule a question
// broke (empty while none did). put() registers them with the call and sends only a number.
template <class T>
struct judge_occlusion {
    std::shared_ptr<test::occlusion_server<T>> server;
    std::shared_ptr<std::string> fault = std::make_shared<std::string>();
};

template <class T>
void put(writer& w, const judge_occlusion<T>& c) {
    put(w, judge_keep_callback([server = c.server, fault = c.fault](reader& in, writer& out) {
        ray<T> r{};
        interval<T> range{};
        get(in, r);
        get(in, range);
        bool blocked = false;
        try {
            blocked = server->answer(r, range);
        } catch (const std::logic_error& e) {
            if (fault->empty()) *fault = e.what();
        }
        put(out, blocked);
    }));
}

// Runner side: the student's shade() calls this; it asks the judge.
template <class T>
void get(reader& r, std::function<bool(const ray<T>&, const interval<T>&)>& f) {
    std::uint32_t id = 0;
    get(r, id);
    f = [id](const ray<T>& ray_, const interval<T>& range) {
        writer arguments;
        put(arguments, ray_);
        put(arguments, range);
        const std::string answer = runner_call_back(id, arguments.bytes());
        reader in(answer);
        bool blocked = false;
        get(in, blocked);
        return blocked;
    };
}

}  // namespace rt::rpc
