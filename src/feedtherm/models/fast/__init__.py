"""The fast model: a thermal network with the screw resolved along its axis and a moving nut."""
