#!/usr/bin/env python3
"""The shipped STM32F103C8 (Blue Pill) firmware ELF, run instruction by instruction in the
Unicorn engine (a Cortex-M3) with a model of the peripherals it touches, deep enough for it
(RM0008 register by register): the bytes it clocks out of SPI1, with the DC level of each, go
to a stream file that the panel model decodes (crates/zrow-st7789/examples/replay.rs). What
both boards share is in board.py.

Modelled: flash (64 KB) and SRAM (20 KB) from the memory map, so a firmware whose stack runs
past the bottom of SRAM faults; RCC (ready bits follow their enable bits, the system clock
switch follows its request), FLASH ACR, AFIO MAPR, GPIOA (CRL/CRH configuration, output levels
through ODR, BSRR and BRR: backlight PA1, reset PA2, DC PA3, CS PA4, each change recorded),
SPI1 (as on the F411), DMA1 channel 3 (SPI1_TX, memory to SPI1's DR: a transfer takes its bytes
when enabled and completes after they have shifted out, setting TCIF3 and GIF3), and what
board.py models. Any other access is reported by address and name, and fails the run.

Time: one instruction is taken as one cycle at the firmware's 72 MHz (an estimate, rougher than
on the M4: the M3 has no FPU, so f32 arithmetic is library calls, counted as their
instructions). SPI bytes take 8 clocks of SCK (PCLK2 / 2^(BR+1)).

usage: f103.py ELF STREAM --frames-per-scene N --frames M --scenes interlocked,cube [--profile N]
       f103.py ELF --self-test   (an access the model does not know must fail the run)
"""

from unicorn.arm_const import UC_CPU_ARM_CORTEX_M3

import board
from board import SPI1

AFIO = 0x4001_0000
GPIOA = 0x4001_0800
DMA1 = 0x4002_0000
C3 = DMA1 + 0x08 + 20 * 2  # channel 3's CCR; CNDTR, CPAR, CMAR follow
RCC = 0x4002_1000
FLASH_ACR = 0x4002_2000

NAMES = {}
name = board.namer(NAMES)
name(RCC, {0x00: "RCC_CR", 0x04: "RCC_CFGR", 0x08: "RCC_CIR", 0x0C: "RCC_APB2RSTR",
           0x10: "RCC_APB1RSTR", 0x14: "RCC_AHBENR", 0x18: "RCC_APB2ENR", 0x1C: "RCC_APB1ENR",
           0x20: "RCC_BDCR", 0x24: "RCC_CSR"})
name(FLASH_ACR, {0: "FLASH_ACR"})
name(AFIO, {0x00: "AFIO_EVCR", 0x04: "AFIO_MAPR"})
name(GPIOA, {0x00: "GPIOA_CRL", 0x04: "GPIOA_CRH", 0x08: "GPIOA_IDR", 0x0C: "GPIOA_ODR",
             0x10: "GPIOA_BSRR", 0x14: "GPIOA_BRR", 0x18: "GPIOA_LCKR"})
name(DMA1, {0x00: "DMA1_ISR", 0x04: "DMA1_IFCR"})
for c in range(1, 8):
    name(DMA1 + 0x08 + 20 * (c - 1), {0x00: f"DMA1_CCR{c}", 0x04: f"DMA1_CNDTR{c}",
                                      0x08: f"DMA1_CPAR{c}", 0x0C: f"DMA1_CMAR{c}"})

# The F103's peripheral blocks (RM0008, memory map), to name an unmodelled access's block.
BLOCKS = [(0x4000_0000, "TIM2"), (0x4000_0400, "TIM3"), (0x4000_0800, "TIM4"),
          (0x4000_2800, "RTC"), (0x4000_2C00, "WWDG"), (0x4000_3000, "IWDG"),
          (0x4000_3800, "SPI2"), (0x4000_4400, "USART2"), (0x4000_4800, "USART3"),
          (0x4000_5400, "I2C1"), (0x4000_5800, "I2C2"), (0x4000_5C00, "USB"),
          (0x4000_6400, "CAN"), (0x4000_6C00, "BKP"), (0x4000_7000, "PWR"),
          (0x4001_0000, "AFIO"), (0x4001_0400, "EXTI"), (0x4001_0800, "GPIOA"),
          (0x4001_0C00, "GPIOB"), (0x4001_1000, "GPIOC"), (0x4001_1400, "GPIOD"),
          (0x4001_1800, "GPIOE"), (0x4001_2400, "ADC1"), (0x4001_2800, "ADC2"),
          (0x4001_2C00, "TIM1"), (0x4001_3000, "SPI1"), (0x4001_3800, "USART1"),
          (0x4002_0000, "DMA1"), (0x4002_1000, "RCC"), (0x4002_2000, "FLASH"),
          (0x4002_3000, "CRC")]


class F103(board.Board):
    NAME = "f103"
    CPU = UC_CPU_ARM_CORTEX_M3
    HCLK = 72_000_000
    FLASH_SIZE, SRAM_SIZE = 64 * 1024, 20 * 1024
    NAMES = NAMES
    # Registers that read back what was written.
    PLAIN = set(NAMES) - {RCC, RCC + 0x04, GPIOA + 0x0C, GPIOA + 0x10, GPIOA + 0x14, DMA1,
                          DMA1 + 4, C3, C3 + 4}
    BLOCKS = BLOCKS
    GPIO_ODR = GPIOA + 0x0C

    def __init__(self, *args):
        super().__init__(*args)
        self.isr = 0

    def chip_read(self, a):
        v = self.regs[a]
        if a == RCC:  # ready bits follow their enables (HSI, HSE, PLL)
            return v | 2 | (v & (1 << 16)) << 1 | (v & (1 << 24)) << 1
        if a == RCC + 0x04:  # SWS follows SW
            return (v & ~0xC) | (v & 3) << 2
        if a == DMA1:  # ISR: the HAL polls channel 3's TCIF until the transfer is done
            if self.dma_end is not None and self.time < self.dma_end:
                self.wait_until(self.dma_end)  # the poll would spin until then
            self.dma_complete()
            return self.isr
        if a == DMA1 + 4:
            return 0
        if a == C3:
            self.dma_complete()
            return self.regs[C3]
        if a == C3 + 4:  # CNDTR: 0 once the transfer is done
            self.dma_complete()
            return 0 if self.dma_end is None else self.regs[C3 + 4]
        return None

    def chip_write(self, a, value):
        if a == GPIOA + 0x10:  # BSRR: set the low half, reset the high half
            self.pin_change((self.odr | (value & 0xFFFF)) & ~(value >> 16))
        elif a == GPIOA + 0x14:  # BRR: reset
            self.pin_change(self.odr & ~(value & 0xFFFF))
        elif a == DMA1 + 4:  # IFCR: channel 3's flags are bits 8..11 (CGIF3 clears all four)
            clear = value & (0xF << 8)
            if value & (1 << 8):
                clear |= 0xF << 8
            self.isr &= ~clear
        elif a == C3:
            was = self.regs[C3]
            self.regs[C3] = value
            if value & 1 and not was & 1:
                self.dma_start()
            elif not value & 1:
                self.dma_complete(aborted=self.dma_end is not None and self.time < self.dma_end)
        elif a in (RCC, RCC + 4, C3 + 4):
            self.regs[a] = value
        else:
            return False
        return True

    # --- DMA1 channel 3 -------------------------------------------------------------------------
    def dma_start(self):
        ccr = self.regs[C3]
        n = self.regs[C3 + 4] & 0xFFFF
        if not ccr & (1 << 4):
            self.errors.append("DMA1 channel 3 enabled, not reading from memory (CCR.DIR clear)")
        if ccr & (1 << 14):
            self.errors.append("DMA1 channel 3 enabled in memory-to-memory mode")
        if self.regs[C3 + 8] != SPI1 + 0x0C:
            self.errors.append(f"DMA1 channel 3 peripheral address {self.regs[C3 + 8]:#x}, "
                               "not SPI1_DR")
        if not self.regs[SPI1 + 4] & 2:
            self.errors.append("DMA1 channel 3 enabled while SPI1_CR2.TXDMAEN is clear")
        if not ccr & (1 << 7) or ccr & (1 << 6):
            self.errors.append("DMA1 channel 3 enabled without memory increment, or with "
                               "peripheral increment")
        if (ccr >> 8) & 0xF != 0:
            self.errors.append("DMA1 channel 3 enabled with transfers wider than a byte")
        self.dma_send(self.regs[C3 + 12], n)

    def dma_complete(self, aborted=False):
        if self.dma_end is None:
            return
        if aborted:
            self.errors.append(f"DMA1 channel 3 disabled at cycle {self.time} before its transfer "
                               f"completed (cycle {self.dma_end})")
        if aborted or self.time >= self.dma_end:
            self.dma_end = None
            if not aborted:
                self.isr |= 0x7 << 8  # GIF3, TCIF3, HTIF3


if __name__ == "__main__":
    # The self-test's probe: USART2's SR, which the firmware never touches.
    board.main(F103, __doc__, (0x4000_4400, "USART2 + 0x0"))
