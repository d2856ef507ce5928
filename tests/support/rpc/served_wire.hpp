// served_wire.hpp — how a served callback travels (served.hpp says what it is).
//
// The judge's stub turns the test's callback into the table for the call's ray (served_for) and sends
// that; the runner reads the table into a callback that answers from it (get below). Nothing goes back:
// the student's code only ever calls the table, and the judge only ever sees the exercise's answer.
#pragma once

#include "served.hpp"
#include "wire.hpp"

#include <stdexcept>

namespace rt::test {
// The served structs travel like the course's others (wire.hpp).
template <class T, class F>
void fields(expected_call<T>& x, F&& f) {
    f(x.object, x.range);
}
template <class T, class F>
void fields(hit_table<T>& x, F&& f) {
    f(x.r, x.count, x.owner, x.records, x.budget, x.check_calls, x.expected);
}
template <class T, class F>
void fields(shadow_answer<T>& x, F&& f) {
    f(x.r, x.range, x.blocked);
}
template <class T, class F>
void fields(occlusion_table<T>& x, F&& f) {
    f(x.answers, x.budget);
}
}  // namespace rt::test

namespace rt::rpc {

// Judge side: the table a test's callback stands for, for this call's ray. A callback that is not a
// served kind cannot run in the runner (it would have to call back into the judge): a test error.
template <class T, class Callback>
test::hit_table<T> served_for(const Callback& f, const ray<T>& r) {
    const auto* served = f.template target<test::served_objects<T>>();
    if (served == nullptr)
        throw std::logic_error("a test gave a callback that is not rt::test::served_objects "
                               "(tests/support/rpc/served.hpp): the grader cannot answer it in the runner");
    return served->table_for(served->only_ray ? *served->only_ray : r);
}

// Runner side: a callback parameter (std::function of either form) is read as a table and answers from it.
template <class T, class Signature>
void get_served(reader& r, std::function<Signature>& f) {
    test::hit_table<T> table;
    get(r, table);
    if (table.owner.size() != table.records.size()) throw protocol_error("a hit table with a record per owner missing");
    f = test::served_table<T>{std::make_shared<test::table_server<T>>(std::move(table))};
}

template <class T>
void get(reader& r, std::function<std::optional<hit_record<T>>(int, const ray<T>&, const interval<T>&)>& f) {
    get_served<T>(r, f);
}
template <class T>
void get(reader& r, std::function<bool(int, const ray<T>&, const interval<T>&, hit_record<T>&)>& f) {
    get_served<T>(r, f);
}

// Chapter 06's occlusion test: the runner answers from the judge's table (served.hpp).
template <class T>
void get(reader& r, std::function<bool(const ray<T>&, const interval<T>&)>& f) {
    test::occlusion_table<T> table;
    get(r, table);
    f = test::served_occlusion_table<T>{std::make_shared<test::occlusion_server<T>>(std::move(table))};
}

}  // namespace rt::rpc
