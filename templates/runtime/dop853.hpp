#pragma once
// Dormand-Prince 8(5,3) explicit Runge-Kutta step (Hairer, Norsett & Wanner, dop853.f).
// Coefficients copied from scipy/integrate/_ivp/dop853_coefficients.py (identical to dop853.f).
// Standard library only: part of the shooting runtime library (runtime.cpp) and of its tests.

#include <algorithm>
#include <cmath>
#include <vector>

namespace helios_rt {

namespace dop853_coeffs {

inline constexpr double C[12] = {
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
};
// A[i][j], stage i = 1..11 (row 0 unused), j < i.
inline constexpr double A[12][12] = {
    {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
    {5.26001519587677318785587544488e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
    {1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
     0.0, 0.0},
    {2.95875854768068491816892993775e-2, 0.0, 8.87627564304205475450678981324e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
     0.0, 0.0},
    {2.41365134159266685502369798665e-1, 0.0, -8.84549479328286085344864962717e-1, 9.24834003261792003115737966543e-1,
     0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
    {3.7037037037037037037037037037e-2, 0.0, 0.0, 1.70828608729473871279604482173e-1,
     1.25467687566822425016691814123e-1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
    {3.7109375e-2, 0.0, 0.0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2, -1.7578125e-2, 0.0,
     0.0, 0.0, 0.0, 0.0, 0.0},
    {3.70920001185047927108779319836e-2, 0.0, 0.0, 1.70383925712239993810214054705e-1,
     1.07262030446373284651809199168e-1, -1.53194377486244017527936158236e-2, 8.27378916381402288758473766002e-3, 0.0,
     0.0, 0.0, 0.0, 0.0},
    {6.24110958716075717114429577812e-1, 0.0, 0.0, -3.36089262944694129406857109825,
     -8.68219346841726006818189891453e-1, 2.75920996994467083049415600797e1, 2.01540675504778934086186788979e1,
     -4.34898841810699588477366255144e1, 0.0, 0.0, 0.0, 0.0},
    {4.77662536438264365890433908527e-1, 0.0, 0.0, -2.48811461997166764192642586468,
     -5.90290826836842996371446475743e-1, 2.12300514481811942347288949897e1, 1.52792336328824235832596922938e1,
     -3.32882109689848629194453265587e1, -2.03312017085086261358222928593e-2, 0.0, 0.0, 0.0},
    {-9.3714243008598732571704021658e-1, 0.0, 0.0, 5.18637242884406370830023853209, 1.09143734899672957818500254654,
     -8.14978701074692612513997267357, -1.85200656599969598641566180701e1, 2.27394870993505042818970056734e1,
     2.49360555267965238987089396762, -3.0467644718982195003823669022, 0.0, 0.0},
    {2.27331014751653820792359768449, 0.0, 0.0, -1.05344954667372501984066689879e1, -2.00087205822486249909675718444,
     -1.79589318631187989172765950534e1, 2.79488845294199600508499808837e1, -2.85899827713502369474065508674,
     -8.87285693353062954433549289258, 1.23605671757943030647266201528e1, 6.43392746015763530355970484046e-1, 0.0},
};
inline constexpr double B[12] = {
    5.42937341165687622380535766363e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.45031289275240888144113950566,
    1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
};
inline constexpr double BHH[3] = {0.244094488188976377952755905512, 0.733846688281611857341361741547,
                                  0.220588235294117647058823529412e-1};
inline constexpr double E5[12] = {
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
};
}  // namespace dop853_coeffs

class Dop853 {
 public:
  // n_err: the error norm is over the first n_err components only (the rest, e.g. variational
  // equations, take the steps the first ones choose); -1: all n.
  explicit Dop853(int n, int n_err = -1)
      : n_(n < 0 ? 0 : n),
        n_err_(n_err < 0 || n_err > n_ ? n_ : n_err),
        k_(static_cast<std::size_t>(n_) * 11),
        ytmp_(static_cast<std::size_t>(n_)),
        ynew_(static_cast<std::size_t>(n_)) {}

  int size() const { return n_; }

  // One step from (t, y) with f0 = f(t, y) of size h. Writes y_new and f_new = f(t+h, y_new) and
  // returns Hairer's combined 5th/3rd order error norm (RMS over components, scaled by
  // sc_i = atol + rtol*max(|y_i|, |y_new_i|)); <= 1 means accept. y_new may alias y and f_new may
  // alias f0: both are written only after the inputs were last read.
  template <class F>
  double step(F& f, double t, const double* y, const double* f0, double h, double* y_new, double* f_new, double atol,
              double rtol) {
    using namespace dop853_coeffs;
    const int n = n_;
    double* const kbuf = k_.data();
    double* const yt = ytmp_.data();
    double* const yn = ynew_.data();
    const double* K[12];
    K[0] = f0;
    for (int s = 1; s < 12; ++s) K[s] = kbuf + (s - 1) * n;
    for (int s = 1; s < 12; ++s) {
      std::fill(yt, yt + n, 0.0);
      for (int j = 0; j < s; ++j) {
        const double a = A[s][j];
        if (a == 0.0) continue;
        const double* kj = K[j];
        for (int i = 0; i < n; ++i) yt[i] += a * kj[i];
      }
      for (int i = 0; i < n; ++i) yt[i] = y[i] + h * yt[i];
      f(t + C[s] * h, static_cast<const double*>(yt), kbuf + (s - 1) * n);
    }

    double err5 = 0.0, err3 = 0.0;
    for (int i = 0; i < n; ++i) {
      double incr = 0.0, e5 = 0.0;
      for (int j = 0; j < 12; ++j) {
        const double kj = K[j][i];
        incr += B[j] * kj;
        e5 += E5[j] * kj;
      }
      yn[i] = y[i] + h * incr;
      if (i >= n_err_) continue;
      const double e3 = incr - BHH[0] * K[0][i] - BHH[1] * K[8][i] - BHH[2] * K[11][i];
      const double sk = atol + rtol * std::max(std::fabs(y[i]), std::fabs(yn[i]));
      err5 += (e5 / sk) * (e5 / sk);
      err3 += (e3 / sk) * (e3 / sk);
    }
    // The 3rd-order term keeps the estimate honest where the 5th-order one is accidentally small.
    double deno = err5 + 0.01 * err3;
    if (deno <= 0.0) deno = 1.0;
    const double err = n_err_ > 0 ? std::fabs(h) * err5 * std::sqrt(1.0 / (n_err_ * deno)) : 0.0;

    std::copy(yn, yn + n, y_new);
    f(t + h, static_cast<const double*>(y_new), f_new);
    return err;
  }

  // Factor for the next step size after a step with error norm err (dop853.f defaults with
  // beta = 0: safety 0.9, exponent 1/8, factor limited to [1/3, 6]). NaN/inf gives the minimum.
  static double step_factor(double err) {
    constexpr double safe = 0.9, fac_min = 0.333, fac_max = 6.0;
    if (err == 0.0) return fac_max;
    if (!(err > 0.0) || !std::isfinite(err)) return fac_min;
    return std::min(fac_max, std::max(fac_min, safe * std::pow(err, -0.125)));
  }

 private:
  int n_;
  int n_err_;
  std::vector<double> k_;     // stages 2..12, n values each
  std::vector<double> ytmp_;  // stage argument
  std::vector<double> ynew_;  // 8th-order solution before it is copied out
};

}  // namespace helios_rt
