// The built-in functions of expressions (ABS ... FLOOR): their values and domain errors.
#include "builtin_functions.hpp"

#include <fmt/format.h>  // messages, ROUND's decimal correction

#include <charconv>  // from_chars
#include <cmath>
#include <numbers>  // pi

#include "gantry/interp/value.hpp"  // format_number for messages

namespace gantry {

namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

[[noreturn]] void bad_argument(const ExprNode& call, int i, std::string message) {
  fail(call.args[i]->start_loc(), std::move(message));
}

// In degrees, whole multiples of 90 give exact results: SIN(180) is 0, not 1.2e-16, and
// TAN(90) is an error rather than 1.6e16. `quadrant` is set (0..3) for those angles.
bool right_angle(double degrees, int* quadrant) {
  const double r = std::fmod(degrees, 360.0);  // exact
  if (std::fmod(r, 90.0) != 0) return false;
  *quadrant = (static_cast<int>(r / 90.0) + 4) % 4;
  return true;
}

double sine(double x, bool degrees) {
  if (!degrees) return std::sin(x);
  int q;
  if (right_angle(x, &q)) return q == 1 ? 1.0 : (q == 3 ? -1.0 : 0.0);
  return std::sin(std::fmod(x, 360.0) * kRadiansPerDegree);
}

double cosine(double x, bool degrees) {
  if (!degrees) return std::cos(x);
  int q;
  if (right_angle(x, &q)) return q == 0 ? 1.0 : (q == 2 ? -1.0 : 0.0);
  return std::cos(std::fmod(x, 360.0) * kRadiansPerDegree);
}

double tangent(const ExprNode& call, double x, bool degrees) {
  if (!degrees) return std::tan(x);
  int q;
  if (right_angle(x, &q)) {
    if (q % 2 == 1)
      bad_argument(
          call, 0,
          fmt::format("TAN of {} degrees is undefined (the cosine is 0)", format_number(x)));
    return 0.0;
  }
  return std::tan(std::fmod(x, 360.0) * kRadiansPerDegree);
}

// Half away from zero, as people round by hand. x * 10^digits carries binary noise
// (2.675 * 100 = 267.49999999999997), so the product is first cut to 15 significant digits,
// which makes ROUND follow the decimal number that was written.
double round_to(double x, double digits) {
  double y = digits >= 0 ? x * std::pow(10.0, digits) : x / std::pow(10.0, -digits);
  if (std::fabs(y) < 1e15) {
    const std::string s = fmt::format("{:.15g}", y);
    std::from_chars(s.data(), s.data() + s.size(), y);
  }
  const double r = std::round(y);
  return digits >= 0 ? r / std::pow(10.0, digits) : r * std::pow(10.0, -digits);
}

}  // namespace

bool uses_angles(ExprFunc f) {
  return f == ExprFunc::Sin || f == ExprFunc::Cos || f == ExprFunc::Tan || f == ExprFunc::Atn ||
         f == ExprFunc::Atan2;
}

double apply_function(const ExprNode& call, const double* args, bool degrees) {
  const double x = args[0];
  double r = 0;
  switch (call.fn) {
    case ExprFunc::Abs:
      r = std::fabs(x);
      break;
    case ExprFunc::Int:
      r = std::floor(x);
      break;
    case ExprFunc::Fix:
      r = std::trunc(x);
      break;
    case ExprFunc::Sgn:
      r = x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
      break;
    case ExprFunc::Sin:
      r = sine(x, degrees);
      break;
    case ExprFunc::Cos:
      r = cosine(x, degrees);
      break;
    case ExprFunc::Tan:
      r = tangent(call, x, degrees);
      break;
    case ExprFunc::Atn:
      r = std::atan(x) * (degrees ? kDegreesPerRadian : 1.0);
      break;
    case ExprFunc::Atan2:
      r = std::atan2(x, args[1]) * (degrees ? kDegreesPerRadian : 1.0);
      break;
    case ExprFunc::Exp:
      r = std::exp(x);
      break;
    case ExprFunc::Log:
      if (x <= 0)
        bad_argument(call, 0,
                     fmt::format("LOG needs a number greater than 0, not {}", format_number(x)));
      r = std::log(x);
      break;
    case ExprFunc::Sqr:
      if (x < 0)
        bad_argument(call, 0,
                     fmt::format("SQR needs a number of at least 0, not {}", format_number(x)));
      r = std::sqrt(x);
      break;
    case ExprFunc::Round: {
      const double digits = call.argc > 1 ? args[1] : 0.0;
      if (digits != std::trunc(digits) || std::fabs(digits) > 15)
        bad_argument(call, 1,
                     fmt::format("ROUND's digits must be a whole number from -15 to 15, not {}",
                                 format_number(digits)));
      r = round_to(x, digits);
      break;
    }
    case ExprFunc::Min:
      r = x;
      for (int i = 1; i < call.argc; ++i) r = std::fmin(r, args[i]);
      break;
    case ExprFunc::Max:
      r = x;
      for (int i = 1; i < call.argc; ++i) r = std::fmax(r, args[i]);
      break;
    case ExprFunc::Ceil:
      r = std::ceil(x);
      break;
    case ExprFunc::Floor:
      r = std::floor(x);
      break;
  }
  if (!std::isfinite(r))
    fail(call.token_loc(),
         fmt::format("the result of {} is too large for a number", function_name(call.fn)));
  return r;
}

}  // namespace gantry
