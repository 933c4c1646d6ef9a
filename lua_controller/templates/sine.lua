-- A travelling sine wave: every joint swings with the same amplitude and
-- frequency, each a quarter period behind the one before it.
-- step(t, state) is called once per control step: t is the sim time (s),
-- state.n the number of joints, state.angles/speeds/torques their readings
-- (1 = the first joint), state.axes "pitch" or "yaw" per joint, state.com
-- the centre of mass. It returns one target angle (rad) per joint.
local amplitude = 0.5         -- rad
local frequency = 0.5         -- Hz
local phase_step = math.pi / 2  -- rad between neighbouring joints

function step(t, state)
  local targets = {}
  for i = 1, state.n do
    targets[i] = amplitude *
        math.sin(2 * math.pi * frequency * t - (i - 1) * phase_step)
  end
  return targets
end
