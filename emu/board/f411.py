#!/usr/bin/env python3
"""The shipped STM32F411 firmware ELF, run instruction by instruction in the Unicorn engine with
a model of the peripherals it touches, deep enough for it (RM0383 register by register): the
bytes it clocks out of SPI1, with the DC level of each, go to a stream file that the panel model
decodes (crates/zrow-st7789/examples/replay.rs). What both boards share is in board.py.

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

usage: f411.py ELF STREAM --frames-per-scene N --frames M [--profile N]
       f411.py ELF --self-test   (an access the model does not know must fail the run)
"""

from unicorn.arm_const import UC_CPU_ARM_CORTEX_M4

import board
from board import SPI1

RCC = 0x4002_3800
FLASH_ACR = 0x4002_3C00
GPIOA = 0x4002_0000
DMA2 = 0x4002_6400
S3 = DMA2 + 0x10 + 0x18 * 3

NAMES = {}
name = board.namer(NAMES)
name(RCC, {0x00: "RCC_CR", 0x04: "RCC_PLLCFGR", 0x08: "RCC_CFGR", 0x0C: "RCC_CIR",
           0x10: "RCC_AHB1RSTR", 0x14: "RCC_AHB2RSTR", 0x20: "RCC_APB1RSTR",
           0x24: "RCC_APB2RSTR", 0x30: "RCC_AHB1ENR", 0x34: "RCC_AHB2ENR", 0x40: "RCC_APB1ENR",
           0x44: "RCC_APB2ENR", 0x84: "RCC_PLLI2SCFGR", 0x8C: "RCC_DCKCFGR"})
name(FLASH_ACR, {0: "FLASH_ACR"})
name(GPIOA, {0x00: "GPIOA_MODER", 0x04: "GPIOA_OTYPER", 0x08: "GPIOA_OSPEEDR",
             0x0C: "GPIOA_PUPDR", 0x10: "GPIOA_IDR", 0x14: "GPIOA_ODR", 0x18: "GPIOA_BSRR",
             0x20: "GPIOA_AFRL", 0x24: "GPIOA_AFRH"})
name(DMA2, {0x00: "DMA2_LISR", 0x04: "DMA2_HISR", 0x08: "DMA2_LIFCR", 0x0C: "DMA2_HIFCR"})
for s in range(8):
    name(DMA2 + 0x10 + 0x18 * s, {0x00: f"DMA2_S{s}CR", 0x04: f"DMA2_S{s}NDTR",
                                  0x08: f"DMA2_S{s}PAR", 0x0C: f"DMA2_S{s}M0AR",
                                  0x10: f"DMA2_S{s}M1AR", 0x14: f"DMA2_S{s}FCR"})

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
          (0x4002_6400, "DMA2")]



class F411(board.Board):
    NAME = "f411"
    CPU = UC_CPU_ARM_CORTEX_M4
    HCLK = 100_000_000
    FLASH_SIZE, SRAM_SIZE = 512 * 1024, 128 * 1024
    NAMES = NAMES
    # Registers that read back what was written.
    PLAIN = set(NAMES) - {RCC, RCC + 0x08, FLASH_ACR, GPIOA + 0x14, GPIOA + 0x18, DMA2,
                          DMA2 + 4, DMA2 + 8, DMA2 + 12, S3, S3 + 4}
    BLOCKS = BLOCKS
    GPIO_ODR = GPIOA + 0x14

    def __init__(self, *args):
        super().__init__(*args)
        self.lisr = 0

    def chip_read(self, a):
        v = self.regs[a]
        if a == RCC:  # ready bits follow their enables (HSI, HSE, PLL, PLLI2S)
            return v | 2 | (v & (1 << 16)) << 1 | (v & (1 << 24)) << 1 | (v & (1 << 26)) << 1
        if a == RCC + 0x08:  # SWS follows SW
            return (v & ~0xC) | (v & 3) << 2
        if a == FLASH_ACR:
            return v
        if a == DMA2:
            if self.dma_end is not None and self.time < self.dma_end:
                self.wait_until(self.dma_end)  # the poll would spin until then
            self.dma_complete()
            return self.lisr
        if a == DMA2 + 4:
            return 0
        if a == S3:
            self.dma_complete()
            return self.regs[S3]
        if a == S3 + 4:
            return 0 if self.dma_end is None else self.regs[S3 + 4]
        return None

    def chip_write(self, a, value):
        if a == GPIOA + 0x18:
            self.pin_change((self.odr | (value & 0xFFFF)) & ~(value >> 16))
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
        elif a in (RCC, RCC + 8, FLASH_ACR, S3 + 4):
            self.regs[a] = value
        else:
            return False
        return True

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
        self.dma_send(self.regs[S3 + 12], n)

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


if __name__ == "__main__":
    # The self-test's probe: USART2's SR, which the firmware never touches.
    board.main(F411, __doc__, (0x4000_4400, "USART2 + 0x0"))
