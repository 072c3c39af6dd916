#pragma once
// Vec3T: a 3-vector of float (the hot path, Embree's precision) or double (the reference
// path that measures what float costs). Points, directions and colours all use it.

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rtiow {

template <typename T>
struct Vec3T {
  T x{}, y{}, z{};

  constexpr Vec3T() = default;
  constexpr Vec3T(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  template <typename U>
  constexpr explicit Vec3T(const Vec3T<U>& v) : x(T(v.x)), y(T(v.y)), z(T(v.z)) {}

  constexpr T operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr T& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3T operator-() const { return {-x, -y, -z}; }
  constexpr Vec3T& operator+=(const Vec3T& v) {
    x += v.x, y += v.y, z += v.z;
    return *this;
  }
  constexpr Vec3T& operator*=(const Vec3T& v) {
    x *= v.x, y *= v.y, z *= v.z;
    return *this;
  }
  constexpr Vec3T& operator*=(T s) {
    x *= s, y *= s, z *= s;
    return *this;
  }
  constexpr bool operator==(const Vec3T&) const = default;
};

using Vec3 = Vec3T<float>;
using Vec3d = Vec3T<double>;
using Color = Vec3T<float>;

template <typename T>
constexpr Vec3T<T> operator+(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename T>
constexpr Vec3T<T> operator-(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
constexpr Vec3T<T> operator*(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <typename T>
constexpr Vec3T<T> operator*(T s, const Vec3T<T>& v) {
  return {s * v.x, s * v.y, s * v.z};
}
template <typename T>
constexpr Vec3T<T> operator*(const Vec3T<T>& v, T s) {
  return s * v;
}
template <typename T>
constexpr Vec3T<T> operator/(const Vec3T<T>& v, T s) {
  return {v.x / s, v.y / s, v.z / s};
}

template <typename T>
constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
constexpr T length_squared(const Vec3T<T>& v) {
  return dot(v, v);
}
template <typename T>
T length(const Vec3T<T>& v) {
  return std::sqrt(dot(v, v));
}
template <typename T>
Vec3T<T> normalize(const Vec3T<T>& v) {
  return v / length(v);
}
template <typename T>
Vec3T<T> abs(const Vec3T<T>& v) {
  return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}
template <typename T>
constexpr T max_component(const Vec3T<T>& v) {
  return std::max(v.x, std::max(v.y, v.z));
}
template <typename T>
bool is_finite(const Vec3T<T>& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// True when every component is so small that the vector has no usable direction.
template <typename T>
bool near_zero(const Vec3T<T>& v) {
  constexpr T s = T(1e-8);
  return std::abs(v.x) < s && std::abs(v.y) < s && std::abs(v.z) < s;
}

// Mirror reflection of v about the unit normal n.
template <typename T>
constexpr Vec3T<T> reflect(const Vec3T<T>& v, const Vec3T<T>& n) {
  return v - T(2) * dot(v, n) * n;
}

// Snell refraction of the unit vector uv through the unit normal n (facing against uv),
// with eta = n_incident / n_transmitted. The caller has checked that refraction is possible.
template <typename T>
Vec3T<T> refract(const Vec3T<T>& uv, const Vec3T<T>& n, T eta) {
  const T cos_theta = std::min(dot(-uv, n), T(1));
  const Vec3T<T> out_perp = eta * (uv + cos_theta * n);
  const Vec3T<T> out_parallel = -std::sqrt(std::abs(T(1) - length_squared(out_perp))) * n;
  return out_perp + out_parallel;
}

}  // namespace rtiow
