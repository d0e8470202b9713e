# catkin_python_setup: the pure-Python part of rotors_sim (src/rotors_sim); the C++ extension
# rotors_sim/_engine is built by CMakeLists.txt into the devel space beside it.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["rotors_sim", "rotors_sim.envs"], package_dir={"": "src"}))
