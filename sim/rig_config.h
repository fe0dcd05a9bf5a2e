#pragma once
// What a rig file (scenarios/rig*.toml) describes: the chamber and its
// controller, the INS case or magnetic shield, the gyro block, the temperature
// sensors and the self-heating. Defaults are the gyro-in-a-magnetic-shield rig
// of the paper's −40..60 °C cycle; the TOML files carry the commented values.
//
// Thermal network (sim/rig_dynamics.h):
//
//   room ──insulation── chamber air ──hA + radiation── case ──G── anode side ──G── sensor (Pt800)
//                          ▲ heater/cooler (PI)           │         │  G
//                                                         └──G── far side ──G── sensor 2
//
// Power: discharge → anode side; dither → half to each side; electronics → case.

namespace gyrotherm::sim {

struct ChamberConfig {
  double capacity_j_per_k = 30000.0;     // air, shelf, fan, inner skin and heater fins
  double insulation_w_per_k = 3.0;       // loss through the insulated walls to the room
  double heater_max_w = 4000.0;
  double cooler_max_w = 3000.0;
  double kp_w_per_k = 2000.0;            // PI proportional gain
  double ti_s = 60.0;                    // PI integral time
  double feedforward_j_per_k = 30000.0;  // set-point-rate feed-forward (≈ capacity)
  double min_c = -60.0;                  // the chamber's working range
  double max_c = 130.0;
};

struct CaseConfig {
  double capacity_j_per_k = 2500.0;      // magnetic shield / INS case with mount
  double convection_w_per_k = 2.0;       // h·A to the chamber air (at 10 K if natural)
  bool natural_convection = false;       // h grows as ΔT^(1/4) (no fan, e.g. a room)
  double emissivity = 0.8;               // radiation to the chamber or room walls
  double area_m2 = 0.12;
};

struct BlockConfig {
  double anode_capacity_j_per_k = 500.0;   // gyro block half with the anode and the Pt800
  double far_capacity_j_per_k = 500.0;     // the opposite half
  double anode_far_w_per_k = 0.5;          // conduction across the block
  double anode_case_w_per_k = 0.4;         // mount and gas gap to the case
  double far_case_w_per_k = 0.6;
};

struct SensorConfig {
  double time_constant_s = 20.0;  // first-order lag of the Pt800 (and the second sensor)
  double noise_c = 0.002;         // white noise of a reading, 1σ
  double resolution_c = 0.001;    // reading quantisation step (0 = none)
};

struct PowerConfig {
  double discharge_w = 1.0;   // plasma discharge, deposited at the anode side
  double dither_w = 0.3;      // dither drive, half to each side of the block
  double electronics_w = 0.0; // electronics inside the case (0 when outside the chamber)
};

struct RigConfig {
  ChamberConfig chamber;
  CaseConfig case_;
  BlockConfig block;
  SensorConfig sensor;
  PowerConfig power;
};

}  // namespace gyrotherm::sim
