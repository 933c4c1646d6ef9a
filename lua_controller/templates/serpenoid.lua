-- Hirose's serpenoid curve: a wave travels along the pitch joints
-- (vertical undulation), the yaw joints hold a bend that steers
-- (0: straight on). The amplitude grows over the first second so the
-- robot does not jerk from rest.
-- step(t, state) is called once per control step: t is the sim time (s),
-- state.n the number of joints, state.axes "pitch" or "yaw" per joint. It
-- returns one target angle (rad) per joint. on_gait_command(cmd) makes it
-- steerable (the studio's arrow keys, mrsim-ctl gait; docs/gait.md).
local alpha = 0.6                 -- rad, wave amplitude
local omega = 2 * math.pi * 0.6   -- rad/s, temporal frequency
local beta = 2 * math.pi / 5      -- rad, phase between pitch joints
local turn = 0.0                  -- rad, bend of every yaw joint
local speed = 1.0                 -- wave strength and direction, -1 to 1

-- Steering: cmd.motion with cmd.strength (-1 to 1). Returning false and a
-- reason refuses a command; returning nothing takes it.
function on_gait_command(cmd)
  local s = cmd.strength or 1
  if cmd.motion == "forward" then speed = s
  elseif cmd.motion == "backward" then speed = -s
  elseif cmd.motion == "turn-left" then turn = 0.3 * s
  elseif cmd.motion == "turn-right" then turn = -0.3 * s
  elseif cmd.motion == "stop" then speed = 0; turn = 0
  elseif cmd.motion then
    return false, "this script steers forward, backward, turn-left, " ..
                  "turn-right and stop, not " .. cmd.motion
  else
    return false, "this script takes motions only (no gait or parameters)"
  end
end

function step(t, state)
  local ramp = math.min(1, t)
  local targets = {}
  local k = 0
  for i = 1, state.n do
    if state.axes and state.axes[i] == "yaw" then
      targets[i] = turn * ramp
    else
      targets[i] = ramp * alpha * math.abs(speed) *
                   math.sin(omega * t - k * beta * (speed < 0 and -1 or 1))
      k = k + 1
    end
  end
  return targets
end
