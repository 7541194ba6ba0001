#include "audio/fft.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>

#include <fftw3.h>

namespace mallet::audio {

namespace {

std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

// FFTW's own aligned buffer, freed with it.
template <typename T>
struct FftwBuffer {
  explicit FftwBuffer(std::size_t n) : data(static_cast<T*>(fftw_malloc(sizeof(T) * n))) {
    if (!data) throw std::bad_alloc();
  }
  ~FftwBuffer() { fftw_free(data); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  T* data;
};

struct Plan {
  explicit Plan(fftw_plan p) : plan(p) {
    if (!plan) throw std::runtime_error("FFTW could not plan a transform");
  }
  ~Plan() {
    std::lock_guard lock(planner_mutex());
    fftw_destroy_plan(plan);
  }
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;
  fftw_plan plan;
};

static_assert(sizeof(fftw_complex) == sizeof(std::complex<double>));

}  // namespace

std::size_t fft_size_for(std::size_t n) {
  std::size_t size = 2;
  while (size < n) size *= 2;
  return size;
}

Spectrum real_dft(std::span<const double> x, std::size_t n) {
  if (n == 0) return {};
  FftwBuffer<double> in(n);
  FftwBuffer<fftw_complex> out(n / 2 + 1);
  const std::size_t copied = std::min(n, x.size());
  std::copy_n(x.begin(), copied, in.data);
  std::fill(in.data + copied, in.data + n, 0.0);
  std::unique_ptr<Plan> plan;
  {
    std::lock_guard lock(planner_mutex());
    plan = std::make_unique<Plan>(fftw_plan_dft_r2c_1d(static_cast<int>(n), in.data, out.data, FFTW_ESTIMATE));
  }
  fftw_execute(plan->plan);
  Spectrum spectrum(n / 2 + 1);
  std::memcpy(static_cast<void*>(spectrum.data()), out.data, sizeof(fftw_complex) * spectrum.size());
  return spectrum;
}

std::vector<double> inverse_real_dft(std::span<const std::complex<double>> spectrum, std::size_t n) {
  if (n == 0) return {};
  if (spectrum.size() != n / 2 + 1) throw std::invalid_argument("inverse_real_dft: n/2 + 1 bins expected");
  FftwBuffer<fftw_complex> in(n / 2 + 1);
  FftwBuffer<double> out(n);
  std::memcpy(in.data, static_cast<const void*>(spectrum.data()), sizeof(fftw_complex) * spectrum.size());
  std::unique_ptr<Plan> plan;
  {
    std::lock_guard lock(planner_mutex());
    // c2r overwrites its input: `in` is ours.
    plan = std::make_unique<Plan>(fftw_plan_dft_c2r_1d(static_cast<int>(n), in.data, out.data, FFTW_ESTIMATE));
  }
  fftw_execute(plan->plan);
  std::vector<double> x(out.data, out.data + n);
  const double scale = 1.0 / static_cast<double>(n);
  for (double& v : x) v *= scale;
  return x;
}

}  // namespace mallet::audio
