"""A compensation law as code a controller runs: C99 (:mod:`.c_code`) and a LinuxCNC HAL component
(:mod:`.linuxcnc`), with the guards a law on a machine needs; ``feedtherm export`` (:mod:`.export`)."""
