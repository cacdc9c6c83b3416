// ----- modules DYNAMICS + SWITCH (template default: two-body Cartesian low thrust) ------------
// y = [r(3), v(3), m, l_r(3), l_v(3), l_m]; control = [u, a(3)] with a unit vector.
// H = lambda0*Tmax/c*(u - eps*u*(1-u)) + l_r.v + l_v.(-mu r/|r|^3 + Tmax u a/m) - l_m Tmax u/c
namespace helios_rt {

void dynamics(double t, const double* y, const double* control, const Multipliers& mult, double* dy) {
  (void)t;
  (void)mult;
  const double* r = y;
  const double* v = y + 3;
  const double m = y[6];
  const double* lr = y + 7;
  const double* lv = y + 10;
  const double u = control[0];
  const double* a = control + 1;
  const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  const double rn = std::sqrt(r2);
  const double mu_r3 = problem::mu / (r2 * rn);
  const double thrust_acc = problem::Tmax * u / m;
  const double lv_dot_r = lv[0] * r[0] + lv[1] * r[1] + lv[2] * r[2];
  const double lv_dot_a = lv[0] * a[0] + lv[1] * a[1] + lv[2] * a[2];
  for (int i = 0; i < 3; ++i) {
    dy[i] = v[i];
    dy[3 + i] = -mu_r3 * r[i] + thrust_acc * a[i];
    // -dH/dr = mu/|r|^3 l_v - 3 mu (l_v.r) r/|r|^5 (the gravity-gradient term)
    dy[7 + i] = mu_r3 * lv[i] - 3.0 * mu_r3 * lv_dot_r * r[i] / r2;
    dy[10 + i] = -lr[i];
  }
  dy[6] = -problem::Tmax * u / problem::c;
  dy[13] = thrust_acc / m * lv_dot_a;
}

double hamiltonian(double t, const double* y, const double* control, const Multipliers& mult) {
  (void)t;
  const double* r = y;
  const double* v = y + 3;
  const double m = y[6];
  const double* lr = y + 7;
  const double* lv = y + 10;
  const double lm = y[13];
  const double u = control[0];
  const double* a = control + 1;
  const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  const double mu_r3 = problem::mu / (r2 * std::sqrt(r2));
  double h =
      mult.lambda0 * problem::Tmax / problem::c * (u - mult.eps * u * (1 - u)) - lm * problem::Tmax * u / problem::c;
  for (int i = 0; i < 3; ++i) h += lr[i] * v[i] + lv[i] * (-mu_r3 * r[i] + problem::Tmax * u * a[i] / m);
  return h;
}

void direction_control(const double* y, double* control) {
  const double* lv = y + 10;
  const double n = std::sqrt(lv[0] * lv[0] + lv[1] * lv[1] + lv[2] * lv[2]);
  for (int i = 0; i < 3; ++i) control[1 + i] = n > 0 ? -lv[i] / n : 0.0;
}

void throttle_slopes(const double* y, const Multipliers& mult, double& at_lower, double& at_upper) {
  const double* lv = y + 10;
  const double m = y[6];
  const double lm = y[13];
  const double base = problem::Tmax / problem::c * (mult.lambda0 - lm) -
                      problem::Tmax * std::sqrt(lv[0] * lv[0] + lv[1] * lv[1] + lv[2] * lv[2]) / m;
  const double curvature = problem::Tmax / problem::c * mult.lambda0 * mult.eps;
  at_lower = base - curvature;
  at_upper = base + curvature;
}

}  // namespace helios_rt
