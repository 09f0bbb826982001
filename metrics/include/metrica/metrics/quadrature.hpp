// Quadrature on a tetrahedron: the Grundmann-Moeller rule of degree 5
// (A. Grundmann, H. M. Moeller, "Invariant integration formulas for the
// n-simplex by combinatorial methods", SIAM J. Numer. Anal. 15, 1978,
// theorem 4 with s = 2): 15 points, exact for every polynomial of degree
// <= 5, some weights negative. Points are barycentric; weights sum to 1,
// so a rule applied to tet T is |T| sum_q w_q f(x_q).
#pragma once

#include <array>
#include <cmath>
#include <vector>

namespace metrica {

struct QuadraturePoint {
  std::array<double, 4> bary;
  double weight;
};

inline const std::vector<QuadraturePoint>& tet_quadrature_degree5() {
  static const std::vector<QuadraturePoint> rule = [] {
    constexpr int n = 3, s = 2, d = 2 * s + 1;
    auto factorial = [](int k) {
      double f = 1;
      for (int i = 2; i <= k; ++i) f *= i;
      return f;
    };
    std::vector<QuadraturePoint> q;
    double total = 0;
    for (int i = 0; i <= s; ++i) {
      // w_i = (-1)^i 2^-2s (d + n - 2i)^d / (i! (d + n - i)!)
      const double w = (i % 2 ? -1.0 : 1.0) * std::pow(2.0, -2.0 * s) * std::pow(d + n - 2.0 * i, d) /
                       (factorial(i) * factorial(d + n - i));
      const int m = s - i;
      // Every beta in N^4 with |beta| = m: barycentric (2 beta_k + 1) / (d + n - 2i).
      for (int b0 = 0; b0 <= m; ++b0)
        for (int b1 = 0; b0 + b1 <= m; ++b1)
          for (int b2 = 0; b0 + b1 + b2 <= m; ++b2) {
            const int b3 = m - b0 - b1 - b2;
            const double den = d + n - 2.0 * i;
            q.push_back({{(2 * b0 + 1) / den, (2 * b1 + 1) / den, (2 * b2 + 1) / den, (2 * b3 + 1) / den}, w});
            total += w;
          }
    }
    for (auto& p : q) p.weight /= total;  // the rule integrates 1 exactly: weights of a unit volume
    return q;
  }();
  return rule;
}

}  // namespace metrica
