// BT.709 Y'CbCr, sRGB to CIELAB, and CIEDE2000.
#include "roving/core/colour_science.h"

#include <cmath>

namespace roving {
namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) {
  return degrees * kPi / 180;
}

double lab_f(double t) {
  constexpr double delta = 6.0 / 29;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29;
}

}  // namespace

double srgb_code(double linear) {
  const double c = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
  return 255 * c;
}

double srgb_linear(double code) {
  const double c = code / 255;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

Vec3 ycbcr_bt709(const Vec3& rgb) {
  const double y = 0.2126 * rgb.x() + 0.7152 * rgb.y() + 0.0722 * rgb.z();
  return Vec3(y, (rgb.z() - y) / 1.8556, (rgb.x() - y) / 1.5748);
}

Vec3 srgb_to_lab(const Vec3& rgb) {
  // IEC 61966-2-1's linear sRGB to XYZ; white is the matrix applied to (1, 1, 1), so that sRGB
  // white is exactly L* = 100, a* = b* = 0.
  static const Eigen::Matrix3d to_xyz = (Eigen::Matrix3d() << 0.4124564, 0.3575761, 0.1804375,  //
                                         0.2126729, 0.7151522, 0.0721750,                       //
                                         0.0193339, 0.1191920, 0.9503041)
                                            .finished();
  static const Vec3 white = to_xyz * Vec3::Ones();
  const Vec3 linear(srgb_linear(rgb.x()), srgb_linear(rgb.y()), srgb_linear(rgb.z()));
  const Vec3 xyz = (to_xyz * linear).cwiseQuotient(white);
  const double fx = lab_f(xyz.x()), fy = lab_f(xyz.y()), fz = lab_f(xyz.z());
  return Vec3(116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz));
}

double ciede2000(const Vec3& lab1, const Vec3& lab2) {
  const double pow25_7 = std::pow(25.0, 7);
  const double c_mean = (std::hypot(lab1.y(), lab1.z()) + std::hypot(lab2.y(), lab2.z())) / 2;
  const double c7 = std::pow(c_mean, 7);
  const double g = 0.5 * (1 - std::sqrt(c7 / (c7 + pow25_7)));
  // a* stretched by G, then chroma and hue in degrees on [0, 360).
  const double a1 = (1 + g) * lab1.y(), a2 = (1 + g) * lab2.y();
  const double c1 = std::hypot(a1, lab1.z()), c2 = std::hypot(a2, lab2.z());
  const auto hue = [](double b, double a) {
    if (a == 0 && b == 0) return 0.0;
    const double h = std::atan2(b, a) * 180 / kPi;
    return h < 0 ? h + 360 : h;
  };
  const double h1 = hue(lab1.z(), a1), h2 = hue(lab2.z(), a2);

  const double delta_l = lab2.x() - lab1.x();
  const double delta_c = c2 - c1;
  double delta_h = 0;
  if (c1 * c2 != 0) {
    delta_h = h2 - h1;
    if (delta_h > 180) delta_h -= 360;
    if (delta_h < -180) delta_h += 360;
  }
  const double delta_big_h = 2 * std::sqrt(c1 * c2) * std::sin(radians(delta_h / 2));

  const double l_bar = (lab1.x() + lab2.x()) / 2;
  const double c_bar = (c1 + c2) / 2;
  double h_bar = h1 + h2;
  if (c1 * c2 != 0) {
    if (std::abs(h1 - h2) <= 180)
      h_bar = (h1 + h2) / 2;
    else
      h_bar = h1 + h2 < 360 ? (h1 + h2 + 360) / 2 : (h1 + h2 - 360) / 2;
  }
  const double t = 1 - 0.17 * std::cos(radians(h_bar - 30)) + 0.24 * std::cos(radians(2 * h_bar)) +
                   0.32 * std::cos(radians(3 * h_bar + 6)) - 0.20 * std::cos(radians(4 * h_bar - 63));
  const double delta_theta = 30 * std::exp(-std::pow((h_bar - 275) / 25, 2));
  const double c_bar7 = std::pow(c_bar, 7);
  const double r_c = 2 * std::sqrt(c_bar7 / (c_bar7 + pow25_7));
  const double l50 = (l_bar - 50) * (l_bar - 50);
  const double s_l = 1 + 0.015 * l50 / std::sqrt(20 + l50);
  const double s_c = 1 + 0.045 * c_bar;
  const double s_h = 1 + 0.015 * c_bar * t;
  const double r_t = -std::sin(radians(2 * delta_theta)) * r_c;
  const double l = delta_l / s_l, c = delta_c / s_c, h = delta_big_h / s_h;
  return std::sqrt(std::max(0.0, l * l + c * c + h * h + r_t * c * h));
}

}  // namespace roving
