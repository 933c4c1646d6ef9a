-- A serpenoid controller whose constants mrsim-opt tunes:
--   mrsim-opt --task flat --controller lua:examples/optimise/serpenoid_params.lua ...
-- A wave travels along the pitch joints (vertical undulation, as the
-- built-in "forward" gait); the yaw joints stay straight.
--
-- `params` declares the tunable constants, in gene order: each entry's
-- name, its range [min, max] and its start value. mrsim-opt makes each a
-- gene; before each episode the global table P holds the genome's values
-- (P.amplitude, ...). Run directly (mrsim-lua --script this file), P holds
-- the start values. Read P inside step(): it is set after the top level.
params = {
  {name = "amplitude", min = 0.0, max = 1.5, start = 1.0},  -- rad
  {name = "phase_lag", min = 0.0, max = 3.14, start = 2.5}, -- rad, joint to joint
  {name = "period", min = 1.0, max = 6.0, start = 4.0},     -- s, of the wave
  {name = "offset", min = -0.3, max = 0.3, start = 0.0},    -- rad, of every pitch joint
}

function step(t, state)
  -- The wave grows over the first second, so the robot does not jerk
  -- from rest.
  local ramp = math.min(1, t)
  local omega = 2 * math.pi / P.period
  local targets = {}
  local k = 0
  for i = 1, state.n do
    if state.axes and state.axes[i] == "yaw" then
      targets[i] = 0
    else
      targets[i] = ramp * (P.amplitude * math.sin(omega * t + k * P.phase_lag)
                           + P.offset)
      k = k + 1
    end
  end
  return targets
end
