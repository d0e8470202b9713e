"""The processes of the graph's nodes, for client functions: a node's pid from the master, whether a
pid lives (not a zombie), its CPU seconds."""

import os
import xmlrpc.client

import rosgraph


def node_pid(name: str) -> int:
    uri = rosgraph.Master("/pytest_client").lookupNode(name)
    return xmlrpc.client.ServerProxy(uri).getPid("/pytest_client")[2]


def _stat_fields(pid: int) -> list:
    return open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()


def alive(pid: int) -> bool:
    try:
        return _stat_fields(pid)[0] != "Z"
    except OSError:
        return False


def cpu_seconds(pid: int) -> float:
    fields = _stat_fields(pid)
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
