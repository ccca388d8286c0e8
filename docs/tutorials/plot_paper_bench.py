"""
The paper's bench in five minutes
=================================

Load the bundled bench of the paper, run the fast model for an hour at one of its measured
conditions and plot what the sensors read.
"""

# %%
# Load the bench
# --------------
#
# ``ft.load`` reads and validates a description: a bundled bench by name or a TOML file.

import matplotlib.pyplot as plt

import feedtherm as ft

loaded = ft.load("paper")
print(loaded.system.meta.title)
print(len(loaded.system.sources), "heat sources:")
print("\n".join(loaded.system.sources))

# %%
# Run condition I for an hour
# ---------------------------
#
# The fast model (a thermal network) with the table's motion averaged over a stroke: seconds,
# not minutes.  The run's series come back as a table, a column per sensor with its unit.

run = ft.simulate(loaded, condition="I", duration=3600.0,
                  motion="averaged")
sensors = run.to_dataframe("sensors")
print(sensors.tail(3).round(1).to_string(index=False))

# %%
# Plot the sensors
# ----------------

fig, ax = plt.subplots(figsize=(7, 4))
minutes = sensors["time [s]"] / 60.0
for column in sensors.columns:
    if column.endswith("[degC]"):
        name = column.removesuffix(" [degC]")
        ax.plot(minutes, sensors[column], label=name)
ax.set_xlabel("time [min]")
ax.set_ylabel("temperature [°C]")
ax.legend(ncol=3)
fig.tight_layout()
