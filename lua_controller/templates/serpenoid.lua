-- Hirose's serpenoid curve: a wave travels along the pitch joints
-- (vertical undulation), the yaw joints hold a bend that steers
-- (0: straight on). The amplitude grows over the first second so the
-- robot does not jerk from rest.
-- step(t, state) is called once per control step: t is the sim time (s),
-- state.n the number of joints, state.axes "pitch" or "yaw" per joint. It
-- returns one target angle (rad) per joint.
local alpha = 0.6                 -- rad, wave amplitude
local omega = 2 * math.pi * 0.6   -- rad/s, temporal frequency
local beta = 2 * math.pi / 5      -- rad, phase between pitch joints
local turn = 0.0                  -- rad, bend of every yaw joint

function step(t, state)
  local ramp = math.min(1, t)
  local targets = {}
  local k = 0
  for i = 1, state.n do
    if state.axes and state.axes[i] == "yaw" then
      targets[i] = turn * ramp
    else
      targets[i] = ramp * alpha * math.sin(omega * t - k * beta)
      k = k + 1
    end
  end
  return targets
end
