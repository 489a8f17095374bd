#!/usr/bin/env python3
"""Writes robots that differ from igus_op.urdf as real ones differ from their model (issue 20):
the trunk 10 % heavier or lighter (mass and inertia), the trunk's centre of mass 1 cm off
forward, backward, left or right, and the leg links of one side 5 % heavier (mass and
inertia). Each is a complete URDF for `stride sim --urdf`, `stride-fw --hal sim --urdf` or a
task config's `urdf` field.

    python3 sim_hal/models/make_variants.py OUT_DIR     # writes OUT_DIR/<variant>.urdf
"""
import argparse
import os
import re
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
LEG = re.compile(r'^(left|right)_(hip_yaw|hip_roll|thigh|shank|ankle|foot)_link$')
INERTIA = ('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz')


def scale_link(link, factor):
    inertial = link.find('inertial')
    mass = inertial.find('mass')
    mass.set('value', repr(float(mass.get('value')) * factor))
    inertia = inertial.find('inertia')
    for key in INERTIA:
        inertia.set(key, repr(float(inertia.get(key)) * factor))


def shift_com(link, dx, dy):
    origin = link.find('inertial').find('origin')
    x, y, z = (float(v) for v in origin.get('xyz').split())
    origin.set('xyz', '%r %r %r' % (x + dx, y + dy, z))


def variants():
    yield 'trunk_mass_plus_10pct', lambda links: scale_link(links['trunk_link'], 1.10)
    yield 'trunk_mass_minus_10pct', lambda links: scale_link(links['trunk_link'], 0.90)
    for name, dx, dy in (('forward', 0.01, 0), ('backward', -0.01, 0), ('left', 0, 0.01),
                         ('right', 0, -0.01)):
        yield 'trunk_com_1cm_' + name, lambda links, dx=dx, dy=dy: shift_com(
            links['trunk_link'], dx, dy)
    for side in ('left', 'right'):
        def heavier(links, side=side):
            for name, link in links.items():
                m = LEG.match(name)
                if m and m.group(1) == side:
                    scale_link(link, 1.05)
        yield side + '_leg_plus_5pct', heavier


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('out_dir', help='folder for the variants (made if missing)')
    out = ap.parse_args().out_dir
    os.makedirs(out, exist_ok=True)
    for name, change in variants():
        tree = ET.parse(os.path.join(HERE, 'igus_op.urdf'))
        links = {link.get('name'): link for link in tree.getroot().iter('link')}
        change(links)
        tree.getroot().set('name', 'igus_op_' + name)
        path = os.path.join(out, name + '.urdf')
        tree.write(path + '.tmp', encoding='unicode', xml_declaration=True)
        os.replace(path + '.tmp', path)
        print(path)


if __name__ == '__main__':
    main()
