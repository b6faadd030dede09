// SPDX-License-Identifier: GPL-2.0
#include "advee/diagcenter/sensor_layout.hpp"

#include <array>

namespace advee::diagcenter {

namespace {
// driver_rs485a.yaml, sd1 "front" (ids 0..7) and "rear" (ids 8..15).
constexpr std::array kSrfs{
    SensorPlace{0, 0.80, 0.25, 60},     SensorPlace{1, 0.85, 0.18, 35},
    SensorPlace{2, 0.88, 0.08, 12},     SensorPlace{3, 0.88, -0.08, -12},
    SensorPlace{4, 0.85, -0.18, -35},   SensorPlace{5, 0.80, -0.25, -60},
    SensorPlace{6, 0.60, 0.28, 90},     SensorPlace{7, 0.60, -0.28, -90},
    SensorPlace{8, -0.15, 0.25, 120},   SensorPlace{9, -0.20, 0.18, 145},
    SensorPlace{10, -0.22, 0.08, 168},  SensorPlace{11, -0.22, -0.08, -168},
    SensorPlace{12, -0.20, -0.18, -145}, SensorPlace{13, -0.15, -0.25, -120},
    SensorPlace{14, 0.05, 0.28, 90},    SensorPlace{15, 0.05, -0.28, -90},
};
}  // namespace

std::span<const SensorPlace> default_srf_layout() { return kSrfs; }

}  // namespace advee::diagcenter
