"""What the board-in-the-loop models of the two demo boards share (`f411.py`, `f103.py`): the
Unicorn CPU with flash and SRAM from the chip's memory map, time, the wire (SPI1's bytes with
the DC level of each, to a stream file the panel model decodes:
crates/zrow-st7789/examples/replay.rs), GPIOA's pins of the demo's wiring (backlight PA1,
reset PA2, DC PA3, CS PA4, each change recorded), the Cortex-M core registers the firmware
touches (SysTick: COUNTFLAG after reload + 1 counts of the core clock or HCLK / 8, a poll that
would spin fast-forwards the clock to the wrap, as the wait would take; DWT CYCCNT; the SCB's
CPACR and the DCB's DEMCR), the peripheral bit-band alias, the frame markers
(`zrow_frame_done`), and the stack's deepest point (the lowest stack pointer at the start of a
block; one below the statics, `_stack_end`, fails the run). A chip's
file models its own registers (`chip_read`, `chip_write`); any access neither knows is
reported by address and name, and fails the run.

Time: one instruction is taken as one cycle at the firmware's clock (an estimate: wait states,
multi-cycle instructions and the bus differ). SPI bytes take 8 clocks of SCK (PCLK2 / 2^(BR+1),
PCLK2 = HCLK on both boards).

The emulator is Unicorn (QEMU's CPU core as a library) from its PyPI wheel: it installs in
seconds with no C toolchain, where the Rust `unicorn-engine` crate builds Unicorn's C sources
with CMake on every fresh machine. Instructions are counted per translated block (capstone).

Profile (`--profile N`): the same count kept per block and charged to the function (ELF symbol)
the block starts in, printed as the N functions the run spent most cycles in: where the board's
time goes, from the shipped ELF itself (inlined code is charged to the function it was inlined
into; legacy Rust symbols are demangled, their hashes dropped).
"""

import argparse
import bisect
import collections
import re
import struct
import sys

import capstone
from elftools.elf.elffile import ELFFile
from unicorn import (UC_ARCH_ARM, UC_HOOK_BLOCK, UC_HOOK_CODE, UC_MODE_MCLASS, UC_MODE_THUMB,
                     UC_PROT_EXEC, UC_PROT_READ, Uc, UcError)
from unicorn.arm_const import UC_ARM_REG_PC, UC_ARM_REG_R0, UC_ARM_REG_SP

FLASH, SRAM = 0x0800_0000, 0x2000_0000
SPI1 = 0x4001_3000
PINS = {1: "BL", 2: "RST", 3: "DC", 4: "CS"}
SYST_CSR, SYST_RVR, SYST_CVR = 0xE000_E010, 0xE000_E014, 0xE000_E018
DWT_CYCCNT = 0xE000_1004
CORE_NAMES = {SYST_CSR: "SYST_CSR", SYST_RVR: "SYST_RVR", SYST_CVR: "SYST_CVR",
              0xE000_E01C: "SYST_CALIB", 0xE000_1000: "DWT_CTRL", DWT_CYCCNT: "DWT_CYCCNT",
              0xE000_ED88: "SCB_CPACR", 0xE000_EDFC: "DCB_DEMCR"}
CORE_PLAIN = {0xE000_E014, 0xE000_E01C, 0xE000_1000, 0xE000_ED88, 0xE000_EDFC}
CORE_BLOCKS = [(0xE000_0000, "ITM"), (0xE000_1000, "DWT"), (0xE000_2000, "FPB"),
               (0xE000_E000, "SCS"), (0xE000_E100, "NVIC"), (0xE000_ED00, "SCB"),
               (0xE000_EF00, "SCB/FPU")]
SPI_NAMES = {SPI1: "SPI1_CR1", SPI1 + 4: "SPI1_CR2", SPI1 + 8: "SPI1_SR", SPI1 + 12: "SPI1_DR"}


def namer(names):
    """`name(base, {offset: "REG"})` records a block's register names into `names`."""
    def name(base, regs):
        for off, n in regs.items():
            names[base + off] = n
    return name


class Board:
    """A chip's model: subclasses set the class attributes and model their registers."""

    NAME = "board"
    CPU = None  # Unicorn's CPU model
    HCLK = 0
    FLASH_SIZE = SRAM_SIZE = 0
    NAMES = {}  # register names, for the report of an unmodelled access
    PLAIN = set()  # registers that read back what was written
    BLOCKS = []  # (base, name) of the chip's peripheral blocks
    GPIO_ODR = 0  # GPIOA's output data register

    def __init__(self, elf, stream, frames_per_scene, frames, scenes=None, profile=False):
        self.uc = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
        self.uc.ctl_set_cpu_model(self.CPU)
        self.uc.mem_map(FLASH, self.FLASH_SIZE, UC_PROT_READ | UC_PROT_EXEC)
        self.uc.mem_map(SRAM, self.SRAM_SIZE)
        with open(elf, "rb") as f:
            e = ELFFile(f)
            for seg in e.iter_segments():
                if seg["p_type"] == "PT_LOAD" and seg["p_filesz"] > 0:
                    self.uc.mem_write(seg["p_paddr"], seg.data())
            symbols = {s.name: s["st_value"] for s in e.get_section_by_name(".symtab").iter_symbols()}
        self.stack_end, self.stack_start = symbols["_stack_end"], symbols["_stack_start"]
        self.lowest_sp, self.overflowed = self.stack_start, False
        # Shorter scenes: the firmware reads FRAMES_PER_SCENE at every frame.
        self.uc.mem_write(symbols["FRAMES_PER_SCENE"], struct.pack("<I", frames_per_scene))
        self.frame_done = symbols["zrow_frame_done"] & ~1
        self.frames, self.frames_per_scene = frames, frames_per_scene
        self.out = open(stream, "w")
        self.out.write(f"# zrow board-in-the-loop stream: {elf}\nfps {frames_per_scene}\n"
                       f"hclk {self.HCLK}\n")
        if scenes:
            self.out.write(f"scenes {' '.join(scenes)}\n")
        self.regs = collections.defaultdict(int)
        self.time = 0  # cycles = instructions
        self.written_ns = -1
        self.unmodelled = collections.Counter()
        self.errors = []
        self.odr = 0
        self.spi_free_at = 0  # the cycle the last byte queued on SPI1 has shifted out
        self.dma_end = None  # completion cycle of the running transfer
        self.syst_wrap = None
        self.marks = 0
        self.last_mark = 0
        self.waited = 0
        self.pending = ("", [])
        self.block_len = {}
        self.elf = elf
        self.executed = collections.Counter() if profile else None  # instructions per block
        self.cs = capstone.Cs(capstone.CS_ARCH_ARM, capstone.CS_MODE_THUMB | capstone.CS_MODE_MCLASS)
        for base, size in [(0x4000_0000, 0x8_0000), (0xE000_0000, 0x10_0000)]:
            self.uc.mmio_map(base, size, self.read, base, self.write, base)
        self.uc.mmio_map(0x4200_0000, 0x100_0000, self.bb_read, None, self.bb_write, None)
        self.uc.hook_add(UC_HOOK_BLOCK, self.block)
        self.uc.hook_add(UC_HOOK_CODE, self.mark, begin=self.frame_done, end=self.frame_done)

    def describe(self, a):
        """`GPIOA_ODR`, or the block and offset of an address without a register name."""
        names = {**CORE_NAMES, **SPI_NAMES, **self.NAMES}
        if a in names:
            return names[a]
        block = max((b for b in self.BLOCKS + CORE_BLOCKS if b[0] <= a), default=None)
        if block is None or a - block[0] >= 0x400 and block[0] < 0xE000_0000:
            return "no peripheral"
        return f"{block[1]} + {a - block[0]:#x}"

    # --- time -------------------------------------------------------------------------------
    def block(self, uc, address, size, _):
        n = self.block_len.get(address)
        if n is None:
            code = bytes(uc.mem_read(address, size))
            n = sum(1 for _ in self.cs.disasm_lite(code, address)) or 1
            self.block_len[address] = n
        self.time += n
        if self.executed is not None:
            self.executed[address] += n
        sp = uc.reg_read(UC_ARM_REG_SP)
        if sp < self.lowest_sp:
            self.lowest_sp = sp
            if sp < self.stack_end and not self.overflowed:
                self.overflowed = True
                self.errors.append(f"the stack ran into the statics: sp {sp:#x} below "
                                   f"_stack_end {self.stack_end:#x} at pc {address:#x}")

    def wait_until(self, cycle):
        """A poll of the SPI or the DMA that would spin until `cycle`: the clock goes there, and
        the wait is counted (the sending that rendering did not hide)."""
        self.waited += cycle - self.time
        self.time = cycle

    def syst_tick(self):
        """Cycles per SysTick count: the core clock (CSR.CLKSOURCE set) or HCLK / 8."""
        return 1 if self.regs[SYST_CSR] & 4 else 8

    def syst_period(self):
        return ((self.regs[SYST_RVR] & 0xFF_FFFF) + 1) * self.syst_tick()

    def cycles_per_byte(self):
        br = (self.regs[SPI1] >> 3) & 7
        return 8 * (2 << br)

    # --- the wire -----------------------------------------------------------------------------
    def level(self, pin):
        return (self.odr >> pin) & 1

    def send(self, data, what):
        """Bytes leaving SPI1 now (queued after the ones still shifting out)."""
        if not self.regs[SPI1] & (1 << 6):
            self.errors.append(f"{what}: SPI1 written while disabled (CR1.SPE clear)")
        if self.level(4):
            self.errors.append(f"{what}: {len(data)} bytes with CS high")
        start = max(self.time, self.spi_free_at)
        self.spi_free_at = start + len(data) * self.cycles_per_byte()
        kind = "d" if self.level(3) else "c"
        ns = start * 1_000_000_000 // self.HCLK
        if ns != self.written_ns:
            self.flush()
            self.out.write(f"t {ns}\n")
            self.written_ns = ns
        if self.pending[0] != kind:
            self.flush()
            self.pending = (kind, [])
        self.pending[1].append(bytes(data).hex())

    def flush(self):
        kind, parts = self.pending
        if parts:
            self.out.write(f"{kind} {''.join(parts)}\n")
        self.pending = ("", [])

    def pin_change(self, new):
        changed = self.odr ^ new
        for pin, label in PINS.items():
            if changed >> pin & 1:
                if label in ("DC", "CS") and self.time < self.spi_free_at:
                    self.errors.append(f"{label} changed at cycle {self.time} while SPI1 was still "
                                       f"shifting out bytes (until cycle {self.spi_free_at})")
                if label in ("RST", "BL"):
                    self.flush()
                    record = "r" if label == "RST" else "b"
                    ns = self.time * 1_000_000_000 // self.HCLK
                    self.out.write(f"t {ns}\n{record} {new >> pin & 1}\n")
        self.odr = new

    # --- registers ----------------------------------------------------------------------------
    def read(self, uc, off, size, base):
        a = base + off
        v = self.chip_read(a)
        if v is not None:
            return v & 0xFFFF_FFFF
        v = self.regs[a]
        if a == SPI1 + 0x08:  # TXE, RXNE; BSY while bytes shift out: a poll waits them out
            if self.time < self.spi_free_at:
                self.wait_until(self.spi_free_at)
            v = 0x3
        elif a == SPI1 + 0x0C:
            v = 0
        elif a == self.GPIO_ODR:
            v = self.odr
        elif a == SYST_CSR:  # COUNTFLAG once the count has wrapped
            v = self.regs[a] & 0x7
            if v & 1 and self.syst_wrap is not None:
                if self.time < self.syst_wrap:
                    self.time = self.syst_wrap
                period = self.syst_period()
                while self.syst_wrap <= self.time:
                    self.syst_wrap += period
                v |= 1 << 16
        elif a == SYST_CVR:
            if self.syst_wrap is None:
                v = 0
            else:
                v = max(0, (self.syst_wrap - self.time) // self.syst_tick() - 1) & 0xFF_FFFF
        elif a == DWT_CYCCNT:
            v = self.time & 0xFFFF_FFFF
        elif a not in self.PLAIN | CORE_PLAIN | {SPI1, SPI1 + 4}:
            self.unmodelled[("read", a)] += 1
        return v & 0xFFFF_FFFF

    def write(self, uc, off, size, value, base):
        a = base + off
        if self.chip_write(a, value):
            return
        if a == self.GPIO_ODR:
            self.pin_change(value & 0xFFFF)
        elif a == SPI1 + 0x0C:
            self.send([value & 0xFF], "DR write")
        elif a == SYST_CSR:
            self.regs[a] = value
            if value & 1 and self.syst_wrap is None:
                self.syst_wrap = self.time + self.syst_period()
            elif not value & 1:
                self.syst_wrap = None
            return
        elif a == SYST_CVR:  # any write clears the count: a full period from now
            if self.syst_wrap is not None:
                self.syst_wrap = self.time + self.syst_period()
            return
        elif a == DWT_CYCCNT:
            self.time = value
            return
        elif a not in self.PLAIN | CORE_PLAIN | {SPI1, SPI1 + 4, SPI1 + 8}:
            self.unmodelled[("write", a)] += 1
        self.regs[a] = value

    def chip_read(self, a):
        """The value of a chip register with behaviour, or None."""
        return None

    def chip_write(self, a, value):
        """Whether a write to a chip register with behaviour was handled."""
        return False

    def bb_read(self, uc, off, size, _):
        word, bit = 0x4000_0000 + ((off >> 5) & ~3), ((off >> 5) & 3) * 8 + ((off >> 2) & 7)
        if word >= 0x4008_0000:
            self.unmodelled[("bit-band read", word)] += 1
            return 0
        return (self.read(uc, word - 0x4000_0000, 4, 0x4000_0000) >> bit) & 1

    def bb_write(self, uc, off, size, value, _):
        word, bit = 0x4000_0000 + ((off >> 5) & ~3), ((off >> 5) & 3) * 8 + ((off >> 2) & 7)
        if word >= 0x4008_0000:
            self.unmodelled[("bit-band write", word)] += 1
            return
        v = self.read(uc, word - 0x4000_0000, 4, 0x4000_0000)
        v = v | (1 << bit) if value & 1 else v & ~(1 << bit)
        self.write(uc, word - 0x4000_0000, 4, v, 0x4000_0000)

    # --- a transfer of the chip's SPI1 TX DMA ---------------------------------------------------
    def dma_send(self, src, n):
        """The transfer's bytes leave SPI1 (after any still shifting out); it completes once
        they have."""
        data = self.uc.mem_read(src, n) if n else b""
        self.send(data, "DMA")
        self.dma_end = self.spi_free_at

    # --- frames ---------------------------------------------------------------------------------
    def mark(self, uc, address, size, _):
        frame = uc.reg_read(UC_ARM_REG_R0)
        self.flush()
        # The last row may still be on the wire: the frame is whole once it has left.
        end = max(self.time, self.spi_free_at)
        self.out.write(f"f {frame} {end - self.last_mark} {self.waited}\n")
        self.last_mark = end
        self.waited = 0
        self.marks += 1
        if self.marks >= self.frames:
            uc.emu_stop()

    def run(self, budget):
        sp, pc = struct.unpack("<II", self.uc.mem_read(FLASH, 8))
        self.uc.reg_write(UC_ARM_REG_SP, sp)
        try:
            self.uc.emu_start(pc | 1, 0, count=budget)
        except UcError as e:
            self.errors.append(f"CPU stopped: {e} at pc {self.uc.reg_read(UC_ARM_REG_PC):#x}")
        if self.marks < self.frames:
            self.errors.append(f"only {self.marks} of {self.frames} frames within {budget} "
                               f"instructions (pc {self.uc.reg_read(UC_ARM_REG_PC):#x})")
        return self.run_report()

    def run_report(self):
        """Closes the stream; the errors, unmodelled accesses last."""
        self.flush()
        self.out.close()
        for (kind, a), n in sorted(self.unmodelled.items()):
            self.errors.append(f"{kind} of {self.describe(a)} at {a:#010x} ({n} times): "
                               f"not modelled")
        return self.errors

    def profile(self):
        """Instructions executed per function, most first: (name, count) pairs, each block
        charged to the function symbol it starts in (`?` outside every one)."""
        with open(self.elf, "rb") as f:
            funcs = sorted((s["st_value"] & ~1, s["st_size"], s.name)
                           for s in ELFFile(f).get_section_by_name(".symtab").iter_symbols()
                           if s["st_info"]["type"] == "STT_FUNC" and s["st_size"] > 0)
        starts = [f[0] for f in funcs]
        per = collections.Counter()
        for address, n in self.executed.items():
            i = bisect.bisect_right(starts, address) - 1
            inside = i >= 0 and address < funcs[i][0] + funcs[i][1]
            per[demangle(funcs[i][2]) if inside else "?"] += n
        return per.most_common()

    def stack_peak(self):
        """Bytes of stack the run took at its deepest: from the stack's top to the lowest stack
        pointer seen at the start of a block."""
        return self.stack_start - self.lowest_sp


# Legacy Rust mangling's escapes (`$LT$` is `<`, ...).
ESCAPES = {"SP": "@", "BP": "*", "RF": "&", "LT": "<", "GT": ">", "LP": "(", "RP": ")",
           "C": ","}


def demangle(name):
    """A legacy-mangled Rust symbol (`_ZN4zrow8scanline...17h<hash>E`) as a path without its
    hash (`zrow::scanline::...`); any other name as it is."""
    if not (name.startswith("_ZN") and name.endswith("E")):
        return name
    parts, i, body = [], 3, name[:-1]
    while i < len(body) and body[i].isdigit():
        j = i
        while body[j].isdigit():
            j += 1
        n = int(body[i:j])
        parts.append(body[j:j + n])
        i = j + n
    if parts and re.fullmatch(r"h[0-9a-f]{16}", parts[-1]):
        parts.pop()

    def unescape(p):
        p = p[1:] if p.startswith("_$") else p
        p = re.sub(r"\$u([0-9a-f]+)\$", lambda m: chr(int(m.group(1), 16)), p)
        p = re.sub(r"\$([A-Z]+)\$", lambda m: ESCAPES.get(m.group(1), m.group(0)), p)
        return p.replace("..", "::")
    return "::".join(unescape(p) for p in parts)


def self_test(chip, elf, address, named):
    """An access the model does not know is an error naming it: one `ldr r1, [r0]` from
    `address` (a register the firmware never touches), run from SRAM."""
    board = chip(elf, "/dev/null", 1, 1)
    at = SRAM + chip.SRAM_SIZE // 2
    board.uc.mem_write(at, bytes([0x01, 0x68]))  # ldr r1, [r0]
    board.uc.reg_write(UC_ARM_REG_R0, address)
    board.uc.emu_start(at | 1, 0, count=1)
    errors = [e for e in board.run_report() if f"{named} at {address:#010x}" in e]
    if not errors:
        sys.exit(f"{chip.NAME}: self-test: a read of {named} went unreported")
    print(f"{chip.NAME}: self-test: {errors[0]}")


def main(chip, doc, probe):
    """The command line of a chip's file: `probe` is its self-test's (address, name)."""
    p = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    p.add_argument("elf")
    p.add_argument("stream", nargs="?")
    p.add_argument("--self-test", action="store_true", help="check that unmodelled accesses fail")
    p.add_argument("--frames-per-scene", type=int, default=3)
    p.add_argument("--frames", type=int, default=9)
    p.add_argument("--scenes", help="the demo scenes the firmware shows, comma-separated "
                   "(default: all of zrow_scenes::DEMOS)")
    p.add_argument("--budget", type=int, default=400_000_000, help="instructions at most")
    p.add_argument("--profile", type=int, metavar="N", default=0,
                   help="print the N functions the run spent most cycles in")
    a = p.parse_args()
    if a.self_test:
        return self_test(chip, a.elf, *probe)
    if a.stream is None:
        p.error("a stream file is needed")
    scenes = a.scenes.split(",") if a.scenes else None
    board = chip(a.elf, a.stream, a.frames_per_scene, a.frames, scenes, a.profile > 0)
    errors = board.run(a.budget)
    print(f"{chip.NAME}: {board.marks} frames, {board.time} cycles emulated, stack peak "
          f"{board.stack_peak()} bytes")
    if a.profile:
        per = board.profile()
        total = sum(n for _, n in per)
        print(f"{chip.NAME}: profile: {total} instructions executed (the other "
              f"{board.time - total} cycles: waits for SPI, DMA and SysTick), by function:")
        for name, n in per[:a.profile]:
            print(f"{n:12d} {100 * n / total:5.1f} %  {name}")
    for e in errors[:40]:
        print(f"{chip.NAME}: error: {e}", file=sys.stderr)
    sys.exit(1 if errors else 0)
