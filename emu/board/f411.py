#!/usr/bin/env python3
"""The shipped STM32F411 firmware ELF, run instruction by instruction in the Unicorn engine with
a model of the peripherals it touches, deep enough for it (RM0383 register by register): the
bytes it clocks out of SPI1, with the DC level of each, go to a stream file that the panel model
decodes (crates/zrow-st7789/examples/replay.rs).

Modelled: flash and SRAM from the memory map; RCC (ready bits follow their enable bits, the
system clock switch follows its request), FLASH ACR, GPIOA (mode, speed, alternate function,
output levels: backlight PA1, reset PA2, DC PA3, CS PA4, each change recorded), SPI1 (CR1's
baud rate, CR2's TX DMA enable, SR's TXE and BSY from the bytes still shifting out, DR), DMA2
stream 3 (channel 3, memory to SPI1's DR: a transfer takes its bytes when enabled and completes
after they have shifted out, setting TCIF3), SysTick (COUNTFLAG after reload + 1 counts of the core clock or HCLK / 8; a
poll that would spin fast-forwards the clock to the wrap, as the wait would take), DWT CYCCNT,
the SCB's CPACR and the DCB's DEMCR, and the peripheral bit-band alias. Any other access is
reported by address and name, and fails the run.

Time: one instruction is taken as one cycle at the firmware's 100 MHz (an estimate: wait states,
multi-cycle instructions and the bus differ). SPI bytes take 8 clocks of SCK (PCLK2 / 2^(BR+1)).

usage: f411.py ELF STREAM --frames-per-scene N --frames M
       f411.py ELF --self-test   (an access the model does not know must fail the run)

The emulator is Unicorn (QEMU's CPU core as a library) from its PyPI wheel: it installs in
seconds with no C toolchain, where the Rust `unicorn-engine` crate builds Unicorn's C sources
with CMake on every fresh machine. Instructions are counted per translated block (capstone).
"""

import argparse
import collections
import struct
import sys

import capstone
from elftools.elf.elffile import ELFFile
from unicorn import (UC_ARCH_ARM, UC_HOOK_BLOCK, UC_HOOK_CODE, UC_MODE_MCLASS, UC_MODE_THUMB,
                     UC_PROT_EXEC, UC_PROT_READ, Uc, UcError)
from unicorn.arm_const import UC_ARM_REG_PC, UC_ARM_REG_R0, UC_ARM_REG_SP, UC_CPU_ARM_CORTEX_M4

HCLK = 100_000_000
PCLK2 = HCLK  # APB2 prescaler 1 at 100 MHz
FLASH, FLASH_SIZE = 0x0800_0000, 512 * 1024
SRAM, SRAM_SIZE = 0x2000_0000, 128 * 1024

# Register names, for the report of an unmodelled access.
NAMES = {}


def name(base, regs):
    for off, n in regs.items():
        NAMES[base + off] = n


RCC = 0x4002_3800
name(RCC, {0x00: "RCC_CR", 0x04: "RCC_PLLCFGR", 0x08: "RCC_CFGR", 0x0C: "RCC_CIR",
           0x10: "RCC_AHB1RSTR", 0x14: "RCC_AHB2RSTR", 0x20: "RCC_APB1RSTR",
           0x24: "RCC_APB2RSTR", 0x30: "RCC_AHB1ENR", 0x34: "RCC_AHB2ENR", 0x40: "RCC_APB1ENR",
           0x44: "RCC_APB2ENR", 0x84: "RCC_PLLI2SCFGR", 0x8C: "RCC_DCKCFGR"})
FLASH_ACR = 0x4002_3C00
name(FLASH_ACR, {0: "FLASH_ACR"})
GPIOA = 0x4002_0000
name(GPIOA, {0x00: "GPIOA_MODER", 0x04: "GPIOA_OTYPER", 0x08: "GPIOA_OSPEEDR",
             0x0C: "GPIOA_PUPDR", 0x10: "GPIOA_IDR", 0x14: "GPIOA_ODR", 0x18: "GPIOA_BSRR",
             0x20: "GPIOA_AFRL", 0x24: "GPIOA_AFRH"})
SPI1 = 0x4001_3000
name(SPI1, {0x00: "SPI1_CR1", 0x04: "SPI1_CR2", 0x08: "SPI1_SR", 0x0C: "SPI1_DR"})
DMA2 = 0x4002_6400
name(DMA2, {0x00: "DMA2_LISR", 0x04: "DMA2_HISR", 0x08: "DMA2_LIFCR", 0x0C: "DMA2_HIFCR"})
for s in range(8):
    name(DMA2 + 0x10 + 0x18 * s, {0x00: f"DMA2_S{s}CR", 0x04: f"DMA2_S{s}NDTR",
                                  0x08: f"DMA2_S{s}PAR", 0x0C: f"DMA2_S{s}M0AR",
                                  0x10: f"DMA2_S{s}M1AR", 0x14: f"DMA2_S{s}FCR"})
S3 = DMA2 + 0x10 + 0x18 * 3
name(0xE000_E010, {0: "SYST_CSR", 4: "SYST_RVR", 8: "SYST_CVR", 12: "SYST_CALIB"})
name(0xE000_1000, {0: "DWT_CTRL", 4: "DWT_CYCCNT"})
name(0xE000_ED88, {0: "SCB_CPACR"})
name(0xE000_EDFC, {0: "DCB_DEMCR"})

# Plain registers: what is written is read back.
PLAIN = {a for a in NAMES} - {RCC, RCC + 0x08, FLASH_ACR, SPI1 + 0x08, SPI1 + 0x0C,
                              GPIOA + 0x14, GPIOA + 0x18, DMA2, DMA2 + 4, DMA2 + 8, DMA2 + 12,
                              S3, S3 + 4, 0xE000_E010, 0xE000_E018, 0xE000_1004}

PINS = {1: "BL", 2: "RST", 3: "DC", 4: "CS"}

# The F411's peripheral blocks (RM0383, memory map), to name an unmodelled access's block.
BLOCKS = [(0x4000_0000, "TIM2"), (0x4000_0400, "TIM3"), (0x4000_0800, "TIM4"),
          (0x4000_0C00, "TIM5"), (0x4000_2800, "RTC"), (0x4000_2C00, "WWDG"),
          (0x4000_3000, "IWDG"), (0x4000_3400, "I2S2ext"), (0x4000_3800, "SPI2"),
          (0x4000_3C00, "SPI3"), (0x4000_4000, "I2S3ext"), (0x4000_4400, "USART2"),
          (0x4000_5400, "I2C1"), (0x4000_5800, "I2C2"), (0x4000_5C00, "I2C3"),
          (0x4000_7000, "PWR"), (0x4001_0000, "TIM1"), (0x4001_1000, "USART1"),
          (0x4001_1400, "USART6"), (0x4001_2000, "ADC1"), (0x4001_2C00, "SDIO"),
          (0x4001_3000, "SPI1"), (0x4001_3400, "SPI4"), (0x4001_3800, "SYSCFG"),
          (0x4001_3C00, "EXTI"), (0x4001_4000, "TIM9"), (0x4001_4400, "TIM10"),
          (0x4001_4800, "TIM11"), (0x4001_5000, "SPI5"), (0x4002_0000, "GPIOA"),
          (0x4002_0400, "GPIOB"), (0x4002_0800, "GPIOC"), (0x4002_0C00, "GPIOD"),
          (0x4002_1000, "GPIOE"), (0x4002_1C00, "GPIOH"), (0x4002_3000, "CRC"),
          (0x4002_3800, "RCC"), (0x4002_3C00, "FLASH"), (0x4002_6000, "DMA1"),
          (0x4002_6400, "DMA2"), (0xE000_0000, "ITM"), (0xE000_1000, "DWT"),
          (0xE000_2000, "FPB"), (0xE000_E000, "SCS"), (0xE000_E100, "NVIC"),
          (0xE000_ED00, "SCB"), (0xE000_EF00, "SCB/FPU")]


def describe(a):
    """`GPIOA_ODR`, or the block and offset of an address without a register name."""
    if a in NAMES:
        return NAMES[a]
    block = max((b for b in BLOCKS if b[0] <= a), default=None)
    if block is None or a - block[0] >= 0x400 and block[0] < 0xE000_0000:
        return "no peripheral"
    return f"{block[1]} + {a - block[0]:#x}"


class Board:
    def __init__(self, elf, stream, frames_per_scene, frames):
        self.uc = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
        self.uc.ctl_set_cpu_model(UC_CPU_ARM_CORTEX_M4)
        self.uc.mem_map(FLASH, FLASH_SIZE, UC_PROT_READ | UC_PROT_EXEC)
        self.uc.mem_map(SRAM, SRAM_SIZE)
        with open(elf, "rb") as f:
            e = ELFFile(f)
            for seg in e.iter_segments():
                if seg["p_type"] == "PT_LOAD" and seg["p_filesz"] > 0:
                    self.uc.mem_write(seg["p_paddr"], seg.data())
            symbols = {s.name: s["st_value"] for s in e.get_section_by_name(".symtab").iter_symbols()}
        # Shorter scenes: the firmware reads FRAMES_PER_SCENE at every frame.
        self.uc.mem_write(symbols["FRAMES_PER_SCENE"], struct.pack("<I", frames_per_scene))
        self.frame_done = symbols["zrow_frame_done"] & ~1
        self.frames, self.frames_per_scene = frames, frames_per_scene
        self.out = open(stream, "w")
        self.out.write(f"# zrow board-in-the-loop stream: {elf}\nfps {frames_per_scene}\n")
        self.regs = collections.defaultdict(int)
        self.time = 0  # cycles = instructions
        self.written_ns = -1
        self.unmodelled = collections.Counter()
        self.errors = []
        self.odr = 0
        self.spi_free_at = 0  # the cycle the last byte queued on SPI1 has shifted out
        self.dma_end = None  # completion cycle of the running stream-3 transfer
        self.lisr = 0
        self.syst_wrap = None
        self.marks = 0
        self.last_mark = 0
        self.waited = 0
        self.pending = ("", [])
        self.block_len = {}
        self.cs = capstone.Cs(capstone.CS_ARCH_ARM, capstone.CS_MODE_THUMB | capstone.CS_MODE_MCLASS)
        for base, size in [(0x4000_0000, 0x8_0000), (0xE000_0000, 0x10_0000)]:
            self.uc.mmio_map(base, size, self.read, base, self.write, base)
        self.uc.mmio_map(0x4200_0000, 0x100_0000, self.bb_read, None, self.bb_write, None)
        self.uc.hook_add(UC_HOOK_BLOCK, self.block)
        self.uc.hook_add(UC_HOOK_CODE, self.mark, begin=self.frame_done, end=self.frame_done)

    # --- time -------------------------------------------------------------------------------
    def block(self, uc, address, size, _):
        n = self.block_len.get(address)
        if n is None:
            code = bytes(uc.mem_read(address, size))
            n = sum(1 for _ in self.cs.disasm_lite(code, address)) or 1
            self.block_len[address] = n
        self.time += n

    def wait_until(self, cycle):
        """A poll of the SPI or the DMA that would spin until `cycle`: the clock goes there, and
        the wait is counted (the sending that rendering did not hide)."""
        self.waited += cycle - self.time
        self.time = cycle

    def syst_tick(self):
        """Cycles per SysTick count: the core clock (CSR.CLKSOURCE set) or HCLK / 8."""
        return 1 if self.regs[0xE000_E010] & 4 else 8

    def syst_period(self):
        return ((self.regs[0xE000_E014] & 0xFF_FFFF) + 1) * self.syst_tick()

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
        ns = start * 1_000_000_000 // HCLK
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
                    self.out.write(f"t {self.time * 1_000_000_000 // HCLK}\n{record} {new >> pin & 1}\n")
        self.odr = new

    # --- registers ----------------------------------------------------------------------------
    def read(self, uc, off, size, base):
        a = base + off
        v = self.regs[a]
        if a == RCC:  # ready bits follow their enables (HSI, HSE, PLL, PLLI2S)
            v |= 2 | (v & (1 << 16)) << 1 | (v & (1 << 24)) << 1 | (v & (1 << 26)) << 1
        elif a == RCC + 0x08:  # SWS follows SW
            v = (v & ~0xC) | (v & 3) << 2
        elif a == FLASH_ACR:
            v = self.regs[a]
        elif a == SPI1 + 0x08:  # TXE, RXNE; BSY while bytes shift out: a poll waits them out
            if self.time < self.spi_free_at:
                self.wait_until(self.spi_free_at)
            v = 0x3
        elif a == SPI1 + 0x0C:
            v = 0
        elif a == GPIOA + 0x14:
            v = self.odr
        elif a == DMA2:
            if self.dma_end is not None and self.time < self.dma_end:
                self.wait_until(self.dma_end)  # the poll would spin until then
            self.dma_complete()
            v = self.lisr
        elif a == DMA2 + 4:
            v = 0
        elif a == S3:
            self.dma_complete()
            v = self.regs[S3]
        elif a == S3 + 4:
            v = 0 if self.dma_end is None else self.regs[S3 + 4]
        elif a == 0xE000_E010:  # SysTick CSR: COUNTFLAG once the count has wrapped
            v = self.regs[a] & 0x7
            if v & 1 and self.syst_wrap is not None:
                if self.time < self.syst_wrap:
                    self.time = self.syst_wrap
                period = self.syst_period()
                while self.syst_wrap <= self.time:
                    self.syst_wrap += period
                v |= 1 << 16
        elif a == 0xE000_E018:
            if self.syst_wrap is None:
                v = 0
            else:
                v = max(0, (self.syst_wrap - self.time) // self.syst_tick() - 1) & 0xFF_FFFF
        elif a == 0xE000_1004:
            v = self.time & 0xFFFF_FFFF
        elif a not in PLAIN:
            self.unmodelled[("read", a)] += 1
        return v & 0xFFFF_FFFF

    def write(self, uc, off, size, value, base):
        a = base + off
        if a == GPIOA + 0x14:
            self.pin_change(value & 0xFFFF)
        elif a == GPIOA + 0x18:
            self.pin_change((self.odr | (value & 0xFFFF)) & ~(value >> 16))
        elif a == SPI1 + 0x0C:
            self.send([value & 0xFF], "DR write")
        elif a == DMA2 + 8:  # LIFCR: stream 3's flags are bits 22..27
            self.lisr &= ~value
        elif a == DMA2 + 12:
            pass
        elif a == S3:
            was = self.regs[S3]
            self.regs[S3] = value
            if value & 1 and not was & 1:
                self.dma_start()
            elif not value & 1:
                self.dma_complete(aborted=self.dma_end is not None and self.time < self.dma_end)
            return
        elif a == 0xE000_E010:
            self.regs[a] = value
            if value & 1 and self.syst_wrap is None:
                self.syst_wrap = self.time + self.syst_period()
            elif not value & 1:
                self.syst_wrap = None
            return
        elif a == 0xE000_E018:  # any write clears the count: a full period from now
            if self.syst_wrap is not None:
                self.syst_wrap = self.time + self.syst_period()
            return
        elif a == 0xE000_1004:
            self.time = value
            return
        elif a not in PLAIN and a not in (RCC, RCC + 8, FLASH_ACR, SPI1 + 8, S3 + 4):
            self.unmodelled[("write", a)] += 1
        self.regs[a] = value

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

    # --- DMA2 stream 3 --------------------------------------------------------------------------
    def dma_start(self):
        cr = self.regs[S3]
        n = self.regs[S3 + 4] & 0xFFFF
        if (cr >> 25) & 7 != 3:
            self.errors.append(f"DMA2 stream 3 enabled on channel {(cr >> 25) & 7}, not 3 (SPI1_TX)")
        if (cr >> 6) & 3 != 1:
            self.errors.append("DMA2 stream 3 enabled, not memory-to-peripheral")
        if self.regs[S3 + 8] != SPI1 + 0x0C:
            self.errors.append(f"DMA2 stream 3 peripheral address {self.regs[S3 + 8]:#x}, not SPI1_DR")
        if not self.regs[SPI1 + 4] & 2:
            self.errors.append("DMA2 stream 3 enabled while SPI1_CR2.TXDMAEN is clear")
        if not cr & (1 << 10):
            self.errors.append("DMA2 stream 3 enabled without memory increment")
        src = self.regs[S3 + 12]
        data = self.uc.mem_read(src, n) if n else b""
        self.send(data, "DMA")
        self.dma_end = self.spi_free_at

    def dma_complete(self, aborted=False):
        if self.dma_end is None:
            return
        if aborted:
            self.errors.append(f"DMA2 stream 3 disabled at cycle {self.time} before its transfer "
                               f"completed (cycle {self.dma_end})")
        if aborted or self.time >= self.dma_end:
            self.dma_end = None
            self.regs[S3] &= ~1
            if not aborted:
                self.lisr |= (1 << 27) | (1 << 26)  # TCIF3, HTIF3

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
            self.errors.append(f"{kind} of {describe(a)} at {a:#010x} ({n} times): not modelled")
        return self.errors


def self_test(elf):
    """An access the model does not know is an error naming it: one `ldr r1, [r0]` from
    USART2's SR, run from SRAM."""
    board = Board(elf, "/dev/null", 1, 1)
    board.uc.mem_write(SRAM + 0x1_0000, bytes([0x01, 0x68]))  # ldr r1, [r0]
    board.uc.reg_write(UC_ARM_REG_R0, 0x4000_4400)
    board.uc.emu_start((SRAM + 0x1_0000) | 1, 0, count=1)
    errors = [e for e in board.run_report() if "USART2 + 0x0 at 0x40004400" in e]
    if not errors:
        sys.exit("f411: self-test: a read of USART2_SR went unreported")
    print(f"f411: self-test: {errors[0]}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("elf")
    p.add_argument("stream", nargs="?")
    p.add_argument("--self-test", action="store_true", help="check that unmodelled accesses fail")
    p.add_argument("--frames-per-scene", type=int, default=3)
    p.add_argument("--frames", type=int, default=9)
    p.add_argument("--budget", type=int, default=400_000_000, help="instructions at most")
    a = p.parse_args()
    if a.self_test:
        return self_test(a.elf)
    if a.stream is None:
        p.error("a stream file is needed")
    board = Board(a.elf, a.stream, a.frames_per_scene, a.frames)
    errors = board.run(a.budget)
    print(f"f411: {board.marks} frames, {board.time} cycles emulated")
    for e in errors[:40]:
        print(f"f411: error: {e}", file=sys.stderr)
    sys.exit(1 if errors else 0)


if __name__ == "__main__":
    main()
