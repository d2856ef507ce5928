// The one main() shared by every doctest executable a student builds and runs.
//
// The autograder does not use these executables for its verdicts: it runs the same tests in a judge
// that holds no student code (tests/support/rpc/, tools/grader/README.md "Who decides pass or fail").
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
