// boost::container::small_vector, the lists of a cavity (vertices, tets,
// faces) kept inline up to a size. GCC 12 reports a false overflow in the
// growth path of these vectors once it is inlined into cavity code (a
// zero-size copy it cannot rule out); the warning is switched off for
// boost's lines here, so that no user's build sees it. Include this header,
// not boost's, before any other boost container.
#pragma once

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif
#include <boost/container/small_vector.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
