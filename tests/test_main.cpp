// Boost.Test entry point; each other file in tests/ is one suite (and one CTest entry).
#define BOOST_TEST_MODULE sandcastle
#include <boost/test/unit_test.hpp>
