"""Free local ports for the tests' links."""

import json
import math
import socket
import struct
import threading
import time
import numpy as np
import pytest
import rotors_sim as rs


def free_udp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]
